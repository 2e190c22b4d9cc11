//! Writing output files so that a reader never sees half of one: the text
//! goes to a temporary file beside the target, which is then renamed over
//! it (atomic on one file system). On failure the temporary file is removed
//! and the target is left as it was. The temporary file is registered with
//! [`crate::interrupt`], so a SIGINT or SIGTERM while it exists deletes it.

use std::io::Write;
use std::path::{Path, PathBuf};

/// The temporary path used while writing `path`.
fn temporary(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Writes `bytes` to `path` atomically.
pub(crate) fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let temp = temporary(path);
    let result = crate::interrupt::create_registered(&temp)
        .and_then(|mut file| file.write_all(bytes))
        .and_then(|()| std::fs::rename(&temp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&temp);
    }
    crate::interrupt::unregister(&temp);
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_whole_files_and_leaves_no_temporary() {
        let dir = std::env::temp_dir().join(format!("stickslip-output-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.json");
        write_atomically(&path, b"{}").unwrap();
        write_atomically(&path, b"{\"v\": 1}").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"{\"v\": 1}");
        assert!(!temporary(&path).exists());
        // A target in a missing directory fails without leaving anything.
        let bad = dir.join("missing").join("b.json");
        assert!(write_atomically(&bad, b"x").is_err());
        assert!(!bad.exists() && !temporary(&bad).exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
