//! CSV records as the core writes and reads its own tables (sweep outputs,
//! the design-plane map), without a CSV library in the core.
//!
//! Contract (RFC 4180, with `\n` line ends): a field is written as it is
//! unless it holds a comma, a double quote, a line end or leading or
//! trailing white space, in which case it is enclosed in double quotes
//! with every double quote doubled. [`records`] reads that back, quoted
//! fields spanning lines included, and names the line where a record
//! starts; a quote that is never closed, or text after a closing quote,
//! is an error. What the command line and the figures read from users'
//! files (any dialect) goes through the `csv` crate in the front ends;
//! The tests check this codec against it.

/// One record as a line of CSV, without the line end.
pub(crate) fn line<S: AsRef<str>>(fields: &[S]) -> String {
    let mut out = String::new();
    for (i, field) in fields.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        let field = field.as_ref();
        let quoted = field.contains([',', '"', '\n', '\r'])
            || field.starts_with(char::is_whitespace)
            || field.ends_with(char::is_whitespace);
        if quoted {
            out.push('"');
            out.push_str(&field.replace('"', "\"\""));
            out.push('"');
        } else {
            out.push_str(field);
        }
    }
    out
}

/// A record read back: its fields and the 1-based line it starts on.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Record {
    /// The line of `text` the record starts on (1-based).
    pub(crate) line: usize,
    /// The fields, unquoted.
    pub(crate) fields: Vec<String>,
}

/// Every record of `text` (lines ending in `\n` or `\r\n`; an empty line
/// is a record of one empty field only inside quotes, otherwise skipped).
/// An error is the 1-based line and what is wrong there.
pub(crate) fn records(text: &str) -> Result<Vec<Record>, (usize, String)> {
    let mut out = Vec::new();
    let mut chars = text.chars().peekable();
    let mut line = 1;
    while chars.peek().is_some() {
        let start = line;
        let mut fields = Vec::new();
        let mut field = String::new();
        let mut at_field_start = true;
        let mut ended = false;
        while let Some(c) = chars.next() {
            match c {
                '"' if at_field_start => {
                    // A quoted field: up to the closing quote.
                    loop {
                        match chars.next() {
                            Some('"') if chars.peek() == Some(&'"') => {
                                chars.next();
                                field.push('"');
                            }
                            Some('"') => break,
                            Some(c) => {
                                if c == '\n' {
                                    line += 1;
                                }
                                field.push(c);
                            }
                            None => return Err((start, "a quote is never closed".to_owned())),
                        }
                    }
                    match chars.peek() {
                        None | Some(',') | Some('\n') | Some('\r') => {}
                        Some(c) => {
                            return Err((line, format!("text {c:?} after a closing quote")));
                        }
                    }
                    at_field_start = false;
                }
                ',' => {
                    fields.push(std::mem::take(&mut field));
                    at_field_start = true;
                }
                '\r' if chars.peek() == Some(&'\n') => {}
                '\n' => {
                    line += 1;
                    ended = true;
                    break;
                }
                c => {
                    field.push(c);
                    at_field_start = false;
                }
            }
        }
        let blank = fields.is_empty() && field.is_empty() && at_field_start;
        if blank && (ended || chars.peek().is_none()) {
            continue;
        }
        fields.push(field);
        out.push(Record {
            line: start,
            fields,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::{line, records};
    use proptest::prelude::*;

    /// Fields drawn from characters that need quoting and some that do
    /// not.
    fn fields() -> impl Strategy<Value = Vec<Vec<String>>> {
        let field = proptest::string::string_regex("[a-z0-9 ,\"\n\r.#-]{0,8}").unwrap();
        let record = proptest::collection::vec(field, 1..5);
        proptest::collection::vec(record, 1..6)
    }

    proptest! {
        #[test]
        fn the_csv_crate_reads_what_is_written_and_so_do_we(rows in fields()) {
            // Records of one empty field are blank lines, which both
            // readers skip: leave them out.
            let rows: Vec<Vec<String>> = rows
                .into_iter()
                .filter(|r| !(r.len() == 1 && r[0].is_empty()))
                .collect();
            let text: String = rows.iter().map(|r| line(r) + "\n").collect();
            let mut reader = csv::ReaderBuilder::new()
                .has_headers(false)
                .flexible(true)
                .from_reader(text.as_bytes());
            let theirs: Vec<Vec<String>> = reader
                .records()
                .map(|r| r.unwrap().iter().map(str::to_owned).collect())
                .collect();
            prop_assert_eq!(&theirs, &rows);
            let ours: Vec<Vec<String>> = records(&text)
                .unwrap()
                .into_iter()
                .map(|r| r.fields)
                .collect();
            prop_assert_eq!(&ours, &rows);
        }
    }

    #[test]
    fn plain_fields_are_written_as_they_are_and_special_ones_quoted() {
        assert_eq!(line(&["1", "0.5", "stick-slip"]), "1,0.5,stick-slip");
        assert_eq!(
            line(&["a,b", "say \"x\"", "two\nlines", " pad"]),
            "\"a,b\",\"say \"\"x\"\"\",\"two\nlines\",\" pad\""
        );
        assert_eq!(line(&["", ""]), ",");
    }

    #[test]
    fn what_is_written_reads_back_with_the_line_it_starts_on() {
        let rows = [
            vec!["case", "failure"],
            vec!["0", "motor.slider_mass = -1: must be > 0, got \"-1\""],
            vec!["1", "two\nlines"],
            vec!["2", ""],
        ];
        let text: String = rows.iter().map(|r| line(r) + "\n").collect();
        let read = records(&text).unwrap();
        assert_eq!(read.len(), 4);
        for (r, want) in read.iter().zip(&rows) {
            assert_eq!(&r.fields, want);
        }
        assert_eq!(
            read.iter().map(|r| r.line).collect::<Vec<_>>(),
            [1, 2, 3, 5]
        );
    }

    #[test]
    fn an_unclosed_quote_or_text_after_a_quote_is_an_error_naming_the_line() {
        assert_eq!(records("a,b\n\"open,c\n").unwrap_err().0, 2);
        let (line, reason) = records("1,2\n\"x\"y,1\n").unwrap_err();
        assert_eq!(line, 2);
        assert!(reason.contains("after a closing quote"), "{reason}");
    }
}
