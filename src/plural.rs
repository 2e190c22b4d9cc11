//! Counts in words: `1 period`, `2 periods`, `1 local optimum`, `3 local
//! optima`. Every count the reports print in front of a noun goes through
//! [`count`], so no line says "1 periods".

/// `n` and the noun in the number it takes: `singular` for exactly one,
/// `plural` otherwise (zero included, as English has it).
pub(crate) fn count<N>(n: N, singular: &str, plural: &str) -> String
where
    N: std::fmt::Display + PartialEq + From<u8>,
{
    let noun = if n == N::from(1) { singular } else { plural };
    format!("{n} {noun}")
}

#[cfg(test)]
mod tests {
    use super::count;

    #[test]
    fn one_takes_the_singular_and_every_other_count_the_plural() {
        assert_eq!(count(1u32, "period", "periods"), "1 period");
        assert_eq!(count(0u32, "period", "periods"), "0 periods");
        assert_eq!(
            count(2u64, "local optimum", "local optima"),
            "2 local optima"
        );
        assert_eq!(
            count(1u64, "local optimum", "local optima"),
            "1 local optimum"
        );
    }
}
