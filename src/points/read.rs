//! Point files: one `x y` point a line (spaces, tabs or a comma between), `#` comments, any line
//! ending (`\n`, `\r\n`, old-Mac `\r`); the format of `docs/design.md`, "Command line".

use kurbo::Point;
use rayon::prelude::*;

/// Why a point file could not be read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PointFileError {
    /// A line that should hold a point does not start with two numbers.
    #[error("line {line}: expected two numbers `x y`, found {found:?}")]
    NotAPoint {
        /// 1-based line number.
        line: usize,
        /// The offending line, shortened.
        found: String,
    },
    /// A coordinate is NaN or infinite (or overflows to infinity).
    #[error("line {line}: coordinate {found:?} is not a finite number")]
    NotFinite {
        /// 1-based line number.
        line: usize,
        /// The offending field.
        found: String,
    },
}

/// The points of a point file, with the 1-based line each came from.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PointFile {
    /// The points, in file order.
    pub points: Vec<Point>,
    /// `lines[i]` is the line number of `points[i]`.
    pub lines: Vec<usize>,
    /// The line number of a header line that was skipped, if any.
    pub header_line: Option<usize>,
}

/// Parses a point file.
///
/// Columns after the second are ignored. The first non-comment line may be a header (for example
/// `x,y` from a spreadsheet): if it holds no number at all it is skipped and reported in
/// [`PointFile::header_line`]. Any later line that does not start with two numbers is an error.
///
/// Large files are parsed in pieces on all cores; the result, errors included, is the same as
/// parsing line by line.
///
/// # Examples
///
/// ```
/// use crawltrace::{parse_points, Point, PointFileError};
///
/// let file = parse_points(b"x,y\n0 0\n# a comment\n1.5\t2 ignored\n")?;
/// assert_eq!(file.points, vec![Point::new(0.0, 0.0), Point::new(1.5, 2.0)]);
/// assert_eq!(file.lines, vec![2, 4]);
/// assert_eq!(file.header_line, Some(1));
///
/// let error = parse_points(b"0 0\n1 one\n").unwrap_err();
/// assert_eq!(error.to_string(), "line 2: expected two numbers `x y`, found \"1 one\"");
/// # Ok::<(), PointFileError>(())
/// ```
///
/// # Errors
///
/// [`PointFileError::NotAPoint`] for a line (other than a leading header) that does not start
/// with two numbers, and [`PointFileError::NotFinite`] for a coordinate that is not a finite
/// number; both give the line number.
pub fn parse_points(bytes: &[u8]) -> Result<PointFile, PointFileError> {
    parse_in_pieces(bytes, PIECE_SIZE)
}

/// [`parse_points`] with pieces of about `piece_size` bytes.
fn parse_in_pieces(bytes: &[u8], piece_size: usize) -> Result<PointFile, PointFileError> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let pieces = split_into_pieces(bytes, piece_size);
    let parsed: Vec<Piece> = if pieces.len() == 1 {
        vec![parse_piece(pieces[0])]
    } else {
        pieces.into_par_iter().map(parse_piece).collect()
    };
    // Put the pieces together as one sequential pass would have read them.
    let mut file = PointFile {
        points: Vec::with_capacity(parsed.iter().map(|piece| piece.points.len()).sum()),
        lines: Vec::with_capacity(parsed.iter().map(|piece| piece.lines.len()).sum()),
        header_line: None,
    };
    let mut lines_before = 0;
    let mut content_before = false;
    for piece in parsed {
        if let Some((line, found)) = piece.header {
            if content_before {
                // Only the file's first non-comment line may be a header.
                return Err(PointFileError::NotAPoint {
                    line: lines_before + line,
                    found,
                });
            }
            file.header_line = Some(lines_before + line);
        }
        if let Some(error) = piece.error {
            return Err(error.shifted(lines_before));
        }
        file.points.extend_from_slice(&piece.points);
        file.lines
            .extend(piece.lines.iter().map(|&line| lines_before + line));
        lines_before += piece.line_count;
        content_before |= piece.has_content;
    }
    Ok(file)
}

/// Pieces of about this many bytes are parsed in parallel.
const PIECE_SIZE: usize = 1 << 20;

/// What one piece of a file holds, its line numbers counted from 1 at the piece's start.
#[derive(Default)]
struct Piece {
    points: Vec<Point>,
    lines: Vec<usize>,
    line_count: usize,
    /// The piece's first non-comment line, if it held no number: its line and shortened text.
    header: Option<(usize, String)>,
    /// Whether the piece has a line that is not blank or a comment.
    has_content: bool,
    /// The first bad line after the header, if any (parsing stops there).
    error: Option<PointFileError>,
}

/// Parses `bytes` as if it were a whole file (a header allowed on its first non-comment line).
fn parse_piece(bytes: &[u8]) -> Piece {
    let mut piece = Piece::default();
    for (index, line) in split_lines(bytes).enumerate() {
        piece.line_count = index + 1;
        let line_number = index + 1;
        let content = match line.iter().position(|&b| b == b'#') {
            Some(hash) => &line[..hash],
            None => line,
        };
        let mut fields = content
            .split(|&b| b == b' ' || b == b'\t' || b == b',' || b == b';')
            .filter(|field| !field.is_empty());
        let Some(first) = fields.next() else { continue };
        let is_first_content = !piece.has_content;
        piece.has_content = true;
        let second = fields.next();
        match (parse_number(first), second.map(parse_number)) {
            (Some(x), Some(Some(y))) => {
                for (value, field) in [(x, first), (y, second.unwrap_or_default())] {
                    if !value.is_finite() {
                        piece.error = Some(PointFileError::NotFinite {
                            line: line_number,
                            found: String::from_utf8_lossy(field).into_owned(),
                        });
                        return piece;
                    }
                }
                piece.points.push(Point::new(x, y));
                piece.lines.push(line_number);
            }
            (first_number, second_number) => {
                let holds_no_number = first_number.is_none() && second_number.flatten().is_none();
                if is_first_content && holds_no_number {
                    piece.header = Some((line_number, shorten(content)));
                    continue;
                }
                piece.error = Some(PointFileError::NotAPoint {
                    line: line_number,
                    found: shorten(content),
                });
                return piece;
            }
        }
    }
    piece
}

/// Cuts `bytes` into pieces of about `size` bytes, each ending with a line (never between the
/// `\r` and `\n` of one line ending).
fn split_into_pieces(bytes: &[u8], size: usize) -> Vec<&[u8]> {
    let mut pieces = Vec::new();
    let mut rest = bytes;
    while rest.len() > size {
        let cut = (size..rest.len()).find(|&i| match rest[i - 1] {
            b'\n' => true,
            b'\r' => rest[i] != b'\n',
            _ => false,
        });
        let Some(cut) = cut else { break };
        let (piece, more) = rest.split_at(cut);
        pieces.push(piece);
        rest = more;
    }
    pieces.push(rest);
    pieces
}

impl PointFileError {
    /// The same error with its line number moved on by `lines`.
    fn shifted(self, lines: usize) -> Self {
        match self {
            Self::NotAPoint { line, found } => Self::NotAPoint {
                line: line + lines,
                found,
            },
            Self::NotFinite { line, found } => Self::NotFinite {
                line: line + lines,
                found,
            },
        }
    }
}

/// Splits on `\r\n`, `\n` and lone `\r`.
fn split_lines(bytes: &[u8]) -> impl Iterator<Item = &[u8]> {
    let mut rest = bytes;
    std::iter::from_fn(move || {
        if rest.is_empty() {
            return None;
        }
        match rest.iter().position(|&b| b == b'\n' || b == b'\r') {
            Some(end) => {
                let line = &rest[..end];
                let skip = if rest[end] == b'\r' && rest.get(end + 1) == Some(&b'\n') {
                    2
                } else {
                    1
                };
                rest = &rest[end + skip..];
                Some(line)
            }
            None => {
                let line = rest;
                rest = &[];
                Some(line)
            }
        }
    })
}

fn parse_number(field: &[u8]) -> Option<f64> {
    std::str::from_utf8(field).ok()?.parse().ok()
}

/// How much of a bad field an error message quotes: enough to find it on its line, short enough
/// to keep the message on one line.
const QUOTED_CHARS: usize = 40;

fn shorten(content: &[u8]) -> String {
    let text = String::from_utf8_lossy(content);
    let text = text.trim();
    match text.char_indices().nth(QUOTED_CHARS) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn xy(file: &PointFile) -> Vec<(f64, f64)> {
        file.points.iter().map(|p| (p.x, p.y)).collect()
    }

    #[test]
    fn separators_comments_and_extra_columns() {
        let file =
            parse_points(b"# a comment\n1 2\n3\t4\n5,6\n 7 , 8 ,9 extra\n\n10 11 # trailing\n")
                .unwrap();
        assert_eq!(
            xy(&file),
            vec![(1.0, 2.0), (3.0, 4.0), (5.0, 6.0), (7.0, 8.0), (10.0, 11.0)]
        );
        assert_eq!(file.lines, vec![2, 3, 4, 5, 7]);
    }

    #[test]
    fn every_line_ending_is_accepted() {
        for text in [
            &b"1 2\n3 4\n5 6"[..],
            b"1 2\r\n3 4\r\n5 6\r\n",
            b"1 2\r3 4\r5 6\r",
        ] {
            let file = parse_points(text).unwrap();
            assert_eq!(
                xy(&file),
                vec![(1.0, 2.0), (3.0, 4.0), (5.0, 6.0)],
                "{text:?}"
            );
            assert_eq!(file.lines, vec![1, 2, 3]);
        }
    }

    #[test]
    fn non_finite_values_name_their_line() {
        for bad in ["nan", "inf", "-infinity", "1e999"] {
            let text = format!("1 2\n3 {bad}\n");
            assert_eq!(
                parse_points(text.as_bytes()),
                Err(PointFileError::NotFinite {
                    line: 2,
                    found: bad.to_string()
                })
            );
        }
    }

    #[test]
    fn a_header_is_skipped_only_at_the_top() {
        let file = parse_points(b"\xEF\xBB\xBFx,y\n1,2\n").unwrap();
        assert_eq!(file.header_line, Some(1));
        assert_eq!(xy(&file), vec![(1.0, 2.0)]);
        let error = parse_points(b"1 2\nx y\n").unwrap_err();
        assert!(
            matches!(error, PointFileError::NotAPoint { line: 2, .. }),
            "{error}"
        );
        let error = parse_points(b"1\n").unwrap_err();
        assert!(
            matches!(error, PointFileError::NotAPoint { line: 1, .. }),
            "{error}"
        );
        let error = parse_points(b"# only\n3 apples\n").unwrap_err();
        assert!(
            matches!(error, PointFileError::NotAPoint { line: 2, .. }),
            "{error}"
        );
    }

    #[test]
    fn parsing_in_pieces_gives_what_one_pass_gives() {
        let texts: [&[u8]; 12] = [
            b"1 2\n3 4\n5 6\n7 8\n9 10\n",
            b"x,y\r\n1,2\r\n3,4\r\n5,6\r\n",
            b"# c\r# d\r\rx y\r1 2\r3 4\r5 6",
            b"\n\n\n# only comments\n\n\nx y\n1 2\n3 4\n",
            b"1 2\n3 4\nx y\n5 6\n",
            b"# a\n# b\n# c\n# d\n# e\nx y\nz w\n1 2\n",
            b"1 2\n3 4\n5 6\n7 nan\n9 10\n",
            b"1 2\r\n3 4\r\n5\r\n7 8\r\n",
            b"1 2\n3 4\n5 6\n\xff 7\n",
            b"\xEF\xBB\xBFx;y\n1;2\n3;4 # end\n",
            b"1 2\r\n\r\n\r\n3 4\r\r\n5 6\n\r7 8",
            b"",
        ];
        for text in texts {
            let whole = parse_in_pieces(text, usize::MAX);
            for size in 1..=text.len() + 1 {
                assert_eq!(
                    parse_in_pieces(text, size),
                    whole,
                    "pieces of {size} bytes of {:?}",
                    String::from_utf8_lossy(text)
                );
            }
        }
    }

    #[test]
    fn pieces_end_with_whole_lines() {
        let text = b"1 2\r\n3 4\r5 6\n7 8\r\n";
        for size in 1..text.len() {
            let pieces = split_into_pieces(text, size);
            assert_eq!(pieces.concat(), text);
            for piece in &pieces[..pieces.len() - 1] {
                assert!(matches!(piece.last(), Some(b'\n' | b'\r')), "{pieces:?}");
            }
            for pair in pieces.windows(2) {
                assert!(
                    !(pair[0].ends_with(b"\r") && pair[1].starts_with(b"\n")),
                    "a line ending cut in two: {pieces:?}"
                );
            }
        }
    }

    #[test]
    fn empty_input_has_no_points() {
        assert_eq!(parse_points(b"").unwrap(), PointFile::default());
        assert_eq!(parse_points(b"\n# nothing\n\r\n").unwrap().points.len(), 0);
    }
}
