//! Reading the files a job names (the job file itself, design, curve and spline files):
//! each must be a regular file of bounded size, checked before it is opened, so that a
//! device (`/dev/zero`), a FIFO or a directory is refused at once rather than read
//! until memory runs out or waited on for ever.

use std::io::Read;
use std::path::Path;

/// Checks that `path` is a regular file (symbolic links followed) of at most `max` bytes,
/// and returns its length.
///
/// # Errors
/// A message naming the file and `what` it is: missing, not a regular file, or too large.
pub fn regular(path: &Path, max: u64, what: &str) -> Result<u64, String> {
    let name = path.display();
    let meta = std::fs::metadata(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => format!("{what} not found: {name}"),
        _ => format!("cannot read {what} {name}: {e}"),
    })?;
    if !meta.is_file() {
        return Err(format!(
            "{what} {name} is not a regular file (a directory, device or pipe): name a file"
        ));
    }
    if meta.len() > max {
        return Err(format!(
            "{what} {name} has {} bytes, more than the {} MiB a {what} may have",
            meta.len(),
            max >> 20
        ));
    }
    Ok(meta.len())
}

/// The UTF-8 text of the regular file at `path`, at most `max` bytes ([`regular`]; the
/// read stops at `max + 1` bytes too, should the file grow meanwhile).
///
/// # Errors
/// As [`regular`], and a read error or text that is not UTF-8.
pub fn read_text(path: &Path, max: u64, what: &str) -> Result<String, String> {
    regular(path, max, what)?;
    let name = path.display();
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read {what} {name}: {e}"))?;
    let mut bytes = Vec::new();
    file.take(max + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read {what} {name}: {e}"))?;
    if bytes.len() as u64 > max {
        return Err(format!("{what} {name} is longer than {} MiB", max >> 20));
    }
    String::from_utf8(bytes).map_err(|e| format!("{what} {name} is not UTF-8 text: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_pipes_and_folders_are_refused_before_opening() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_text(dir.path(), 1 << 20, "design file").unwrap_err();
        assert!(e.contains("not a regular file"), "{e}");
        #[cfg(unix)]
        {
            let e = read_text(Path::new("/dev/zero"), 1 << 20, "design file").unwrap_err();
            assert!(e.contains("not a regular file"), "{e}");
            let fifo = dir.path().join("fifo");
            let made = std::process::Command::new("mkfifo").arg(&fifo).status();
            if made.is_ok_and(|s| s.success()) {
                // would block in open() if it were opened
                let e = read_text(&fifo, 1 << 20, "design file").unwrap_err();
                assert!(e.contains("not a regular file"), "{e}");
            }
        }
        let f = dir.path().join("big.json");
        std::fs::write(&f, vec![b' '; 2048]).unwrap();
        assert!(read_text(&f, 1024, "x").unwrap_err().contains("2048 bytes"));
        assert_eq!(read_text(&f, 4096, "x").unwrap().len(), 2048);
    }
}
