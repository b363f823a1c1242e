//! Reading input files: with a cap on their size, without a byte-order mark, and refusing in
//! words what is not a file.
//!
//! Every file a verb or the Python package reads whole (grammars, genomes, creatures,
//! recordings, growths, configurations, a comparison's settings) goes through [`read`] or
//! [`read_to_string`]:
//!
//! - **A cap on the size.** At most [`max_input`] bytes are read: 64 MiB, or what the
//!   environment variable `ONTOGENY_MAX_INPUT` says. A regular file larger than the cap is
//!   refused before anything is read; a stream that never ends (`/dev/zero`, a pipe, standard
//!   input) is refused as soon as one byte more than the cap has arrived, and nothing past it
//!   is read.
//! - **No byte-order mark.** A file that begins with UTF-8's byte-order mark (`EF BB BF`, which
//!   some editors write) is read as if it had none.
//! - **A file, or a stream.** A directory, a block device or a socket given as an input is
//!   refused with what it is; a symbolic link that points nowhere says where it points. A
//!   character device or a fifo is read as a stream.
//!
//! The errors are [`std::io::Error`]s whose messages are written for people ("a directory,
//! not a file"), for the caller to put after the file's name.
//!
//! What this module does not own: what a file means (the rooms that parse it), or the run
//! store, which SQLite reads in pages.

use std::fs;
use std::io::{self, Read};
use std::path::Path;

/// The default cap on an input's size, in bytes: 64 MiB.
pub const DEFAULT_MAX_INPUT: u64 = 64 << 20;

/// The environment variable that sets the cap on an input's size: a number of bytes, or of
/// KiB, MiB or GiB with the suffix `K`, `M` or `G` (`ONTOGENY_MAX_INPUT=512M`).
pub const MAX_INPUT_VARIABLE: &str = "ONTOGENY_MAX_INPUT";

/// UTF-8's byte-order mark.
const BYTE_ORDER_MARK: &[u8] = b"\xEF\xBB\xBF";

/// The cap on an input's size in bytes: [`MAX_INPUT_VARIABLE`] when it is set, else
/// [`DEFAULT_MAX_INPUT`] (set to nothing, it counts as unset). A value that is not a size is
/// an error that says what it should be.
pub fn max_input() -> io::Result<u64> {
    match std::env::var_os(MAX_INPUT_VARIABLE) {
        None => Ok(DEFAULT_MAX_INPUT),
        Some(value) if value.is_empty() => Ok(DEFAULT_MAX_INPUT),
        Some(value) => {
            let text = value.to_string_lossy();
            parse_size(&text).ok_or_else(|| {
                io::Error::new(
                    io::ErrorKind::InvalidInput,
                    format!(
                        "{MAX_INPUT_VARIABLE} must be a size in bytes, above 0 (e.g. 200000000, \
                         or 512M; suffixes K, M and G), not '{text}'"
                    ),
                )
            })
        }
    }
}

/// A size of at least one byte: digits, then an optional `K`, `M` or `G` (binary multiples;
/// a trailing `iB` or `B` is allowed).
fn parse_size(text: &str) -> Option<u64> {
    let text = text.trim();
    let upper = text.to_ascii_uppercase();
    let stripped = upper
        .strip_suffix("IB")
        .or_else(|| upper.strip_suffix('B'))
        .unwrap_or(&upper);
    let (digits, shift) = match stripped.chars().last()? {
        'K' => (&stripped[..stripped.len() - 1], 10),
        'M' => (&stripped[..stripped.len() - 1], 20),
        'G' => (&stripped[..stripped.len() - 1], 30),
        _ => (stripped, 0),
    };
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let number: u64 = digits.parse().ok()?;
    let size = number.checked_mul(1 << shift)?;
    (size > 0).then_some(size)
}

/// A size in words: whole MiB as `64 MiB`, whole KiB as `512 KiB`, else in bytes.
pub fn size_text(bytes: u64) -> String {
    if bytes >= 1 << 20 && bytes.is_multiple_of(1 << 20) {
        format!("{} MiB", bytes >> 20)
    } else if bytes >= 1 << 20 {
        format!("{:.1} MiB", bytes as f64 / (1u64 << 20) as f64)
    } else if bytes >= 1 << 10 && bytes.is_multiple_of(1 << 10) {
        format!("{} KiB", bytes >> 10)
    } else {
        format!("{bytes} bytes")
    }
}

/// How to raise the cap, for a message.
fn raise_it(cap: u64) -> String {
    format!(
        "the most an input may be is {} (set {MAX_INPUT_VARIABLE}, a size in bytes or with a \
         suffix K, M or G, to raise it)",
        size_text(cap)
    )
}

/// The error of a regular file of `len` bytes, more than `cap`.
fn too_large(len: u64, cap: u64) -> io::Error {
    io::Error::new(
        io::ErrorKind::FileTooLarge,
        format!("it is {}; {}", size_text(len), raise_it(cap)),
    )
}

/// The error of a stream that went on past `cap`.
fn endless(cap: u64) -> io::Error {
    io::Error::new(
        io::ErrorKind::FileTooLarge,
        format!(
            "more than {} came from it without an end; {}",
            size_text(cap),
            raise_it(cap)
        ),
    )
}

/// Reads at most `cap` bytes from `stream`; one more is an error ([`endless`]).
fn read_capped(stream: impl Read, cap: u64) -> io::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    stream.take(cap.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > cap {
        return Err(endless(cap));
    }
    Ok(bytes)
}

/// Refuses what `path` is when it is not something to read whole: a directory, a block
/// device, a socket, a dangling symbolic link. Returns whether it is a regular file, and its
/// length.
fn check_readable(path: &Path) -> io::Result<(bool, u64)> {
    let metadata = match fs::metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            if let Ok(target) = fs::read_link(path) {
                return Err(io::Error::new(
                    io::ErrorKind::NotFound,
                    format!(
                        "it is a symbolic link to {}, which does not exist",
                        target.display()
                    ),
                ));
            }
            return Err(e);
        }
        Err(e) => return Err(e),
    };
    let kind = metadata.file_type();
    if kind.is_file() {
        return Ok((true, metadata.len()));
    }
    let what = if kind.is_dir() {
        Some((io::ErrorKind::IsADirectory, "a directory"))
    } else {
        other_kind(&kind)
    };
    match what {
        Some((error, what)) => Err(io::Error::new(error, format!("{what}, not a file"))),
        None => Ok((false, 0)),
    }
}

/// What a file that is neither a regular file nor a directory is, when it cannot be read as a
/// stream (a block device, a socket); `None` for a stream (a character device, a fifo).
#[cfg(unix)]
fn other_kind(kind: &fs::FileType) -> Option<(io::ErrorKind, &'static str)> {
    use std::os::unix::fs::FileTypeExt;
    if kind.is_block_device() {
        Some((io::ErrorKind::InvalidInput, "a block device"))
    } else if kind.is_socket() {
        Some((io::ErrorKind::InvalidInput, "a socket"))
    } else {
        None
    }
}

/// Elsewhere, anything that is not a file or a directory is read as a stream.
#[cfg(not(unix))]
fn other_kind(_: &fs::FileType) -> Option<(io::ErrorKind, &'static str)> {
    None
}

/// The bytes of the file at `path` (`-`: standard input), at most [`max_input`] of them, a
/// leading byte-order mark left out (see the module's documentation).
pub fn read(path: &Path) -> io::Result<Vec<u8>> {
    let cap = max_input()?;
    let mut bytes = if path.as_os_str() == "-" {
        read_capped(io::stdin().lock(), cap)?
    } else {
        let (regular, len) = check_readable(path)?;
        if regular && len > cap {
            return Err(too_large(len, cap));
        }
        // A regular file may have grown since: the cap holds whatever it holds now.
        read_capped(fs::File::open(path)?, cap)?
    };
    if bytes.starts_with(BYTE_ORDER_MARK) {
        bytes.drain(..BYTE_ORDER_MARK.len());
    }
    Ok(bytes)
}

/// The text of the file at `path` as [`read`] reads it, which must be UTF-8.
pub fn read_to_string(path: &Path) -> io::Result<String> {
    text(read(path)?)
}

/// `bytes` as UTF-8 text, or an error that says where it is not.
pub fn text(bytes: Vec<u8>) -> io::Result<String> {
    String::from_utf8(bytes).map_err(|e| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// Makes a symbolic link `name` in `dir` to `to`, which does not exist: where the tests of
/// reading and writing through a dangling link start.
#[cfg(all(test, unix))]
pub(crate) fn dangling_link(dir: &std::path::Path, name: &str, to: &str) -> std::path::PathBuf {
    let link = dir.join(name);
    std::os::unix::fs::symlink(to, &link).unwrap();
    link
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_read_in_bytes_or_binary_multiples() {
        assert_eq!(parse_size("1000"), Some(1000));
        assert_eq!(parse_size("512K"), Some(512 << 10));
        assert_eq!(parse_size("64M"), Some(64 << 20));
        assert_eq!(parse_size("64MiB"), Some(64 << 20));
        assert_eq!(parse_size("2g"), Some(2 << 30));
        assert_eq!(parse_size(" 7 "), Some(7));
        for bad in [
            "",
            "0",
            "M",
            "-1",
            "1.5M",
            "12T",
            "ten",
            "99999999999999999999G",
        ] {
            assert_eq!(parse_size(bad), None, "{bad}");
        }
    }

    #[test]
    fn sizes_are_said_in_the_largest_whole_unit() {
        assert_eq!(size_text(64 << 20), "64 MiB");
        assert_eq!(size_text((65 << 20) + (1 << 19)), "65.5 MiB");
        assert_eq!(size_text(512 << 10), "512 KiB");
        assert_eq!(size_text(1000), "1000 bytes");
    }

    #[test]
    fn a_stream_is_read_to_the_cap_and_refused_one_byte_past_it() {
        assert_eq!(read_capped(&[7u8; 10][..], 10).unwrap(), vec![7; 10]);
        let error = read_capped(io::repeat(0), 1 << 10).unwrap_err();
        assert_eq!(error.kind(), io::ErrorKind::FileTooLarge);
        assert_eq!(
            error.to_string(),
            "more than 1 KiB came from it without an end; the most an input may be is 1 KiB \
             (set ONTOGENY_MAX_INPUT, a size in bytes or with a suffix K, M or G, to raise it)"
        );
    }

    #[test]
    fn a_byte_order_mark_is_left_out_and_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("marked.lsys");
        fs::write(&path, b"\xEF\xBB\xBFaxiom: A\n").unwrap();
        assert_eq!(read_to_string(&path).unwrap(), "axiom: A\n");
        fs::write(&path, "axiom: A\n\u{feff}").unwrap();
        assert_eq!(read_to_string(&path).unwrap(), "axiom: A\n\u{feff}");
    }

    #[test]
    fn a_directory_is_refused_in_words() {
        let dir = tempfile::tempdir().unwrap();
        let error = read(dir.path()).unwrap_err();
        assert_eq!(error.kind(), io::ErrorKind::IsADirectory);
        assert_eq!(error.to_string(), "a directory, not a file");
    }

    #[cfg(unix)]
    #[test]
    fn a_dangling_link_says_where_it_points() {
        let dir = tempfile::tempdir().unwrap();
        let error = read(&dangling_link(dir.path(), "link.lsys", "gone.lsys")).unwrap_err();
        assert_eq!(error.kind(), io::ErrorKind::NotFound);
        assert_eq!(
            error.to_string(),
            "it is a symbolic link to gone.lsys, which does not exist"
        );
    }

    #[test]
    fn text_that_is_not_utf8_says_where() {
        assert_eq!(
            text(b"ab\xFF".to_vec()).unwrap_err().to_string(),
            "not UTF-8 text (invalid byte at offset 2)"
        );
    }
}
