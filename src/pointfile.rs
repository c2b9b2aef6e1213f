//! Point files: one `x y` point a line (spaces, tabs or a comma between), `#` comments, any line
//! ending (`\n`, `\r\n`, old-Mac `\r`); the format of `../shared/DESIGN.md`, "Command line".

use kurbo::Point;

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
pub fn parse_points(bytes: &[u8]) -> Result<PointFile, PointFileError> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let mut file = PointFile::default();
    let mut seen_data = false;
    for (index, line) in split_lines(bytes).enumerate() {
        let line_number = index + 1;
        let content = match line.iter().position(|&b| b == b'#') {
            Some(hash) => &line[..hash],
            None => line,
        };
        let mut fields = content
            .split(|&b| b == b' ' || b == b'\t' || b == b',' || b == b';')
            .filter(|field| !field.is_empty());
        let Some(first) = fields.next() else { continue };
        let second = fields.next();
        match (parse_number(first), second.map(parse_number)) {
            (Some(x), Some(Some(y))) => {
                for (value, field) in [(x, first), (y, second.unwrap_or_default())] {
                    if !value.is_finite() {
                        return Err(PointFileError::NotFinite {
                            line: line_number,
                            found: String::from_utf8_lossy(field).into_owned(),
                        });
                    }
                }
                file.points.push(Point::new(x, y));
                file.lines.push(line_number);
                seen_data = true;
            }
            (first_number, second_number) => {
                let holds_no_number = first_number.is_none() && second_number.flatten().is_none();
                if !seen_data && file.header_line.is_none() && holds_no_number {
                    file.header_line = Some(line_number);
                    seen_data = true;
                    continue;
                }
                return Err(PointFileError::NotAPoint {
                    line: line_number,
                    found: shorten(content),
                });
            }
        }
    }
    Ok(file)
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

fn shorten(content: &[u8]) -> String {
    let text = String::from_utf8_lossy(content);
    let text = text.trim();
    match text.char_indices().nth(40) {
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
    fn empty_input_has_no_points() {
        assert_eq!(parse_points(b"").unwrap(), PointFile::default());
        assert_eq!(parse_points(b"\n# nothing\n\r\n").unwrap().points.len(), 0);
    }
}
