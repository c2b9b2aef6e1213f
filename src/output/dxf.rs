//! Writes a [`Drawing`] as a DXF R2000 (AC1015) file for CAD/CAM and laser software: one
//! `LWPOLYLINE` per curve (closed flag set on closed curves), Béziers flattened within a
//! tolerance, coordinates in millimetres or inches with `$INSUNITS` set, the y axis pointing up
//! as CAD expects, and `dots` as `POINT` entities.
//!
//! DECISION: our own minimal writer rather than the `dxf` crate: that crate is well kept but
//! generates a reader and writer for every entity of every DXF version (with chrono, uuid and
//! encoding_rs) where we write two entity kinds; the structure below is the minimum that the DXF
//! reference and ezdxf's notes on it ("Minimal DXF Content") require of an R13+ file: HEADER
//! with `$ACADVER` and `$HANDSEED`, an empty CLASSES section, the nine tables with their
//! mandatory entries, the model and paper space blocks, the entities, and the root dictionary
//! with `ACAD_GROUP`. `tests/dxf_ezdxf.py` reads the output back and audits it with ezdxf.

use std::fmt::Write as _;

use kurbo::Point;

use super::flatten::flatten_path;
use super::svg::Drawing;
use super::units::{PhysicalSize, Units};

/// Coordinates are written with this many decimals: a tenth of a micrometre in millimetres,
/// 2.5 µm in inches, finer than any machine moves.
const DECIMALS: usize = 4;

/// `$INSUNITS` codes of the DXF reference.
const INSUNITS_INCHES: i32 = 1;
const INSUNITS_MILLIMETRES: i32 = 4;

/// `LWPOLYLINE` flag 70: bit 1 is "closed".
const POLYLINE_CLOSED: i32 = 1;

/// The room the opening view leaves around the drawing, as a share of its size.
const VIEW_MARGIN_SHARE: f64 = 0.05;

/// Writes `drawing` as DXF text at `size` (pixels per inch and units). Every path is flattened
/// within `tolerance` pixels (the fitting tolerance is the natural choice: the flattened
/// polyline then strays from the path by no more than the path strays from the traced curve)
/// into one `LWPOLYLINE`; a path that flattens to a single point, and every point of
/// `drawing.dots`, is a `POINT`. `drawing.points` (a display aid of `points --show-points`) is not
/// written. The drawing's top-left pixel corner is the origin's row: x grows to the right and y
/// upwards, so the image spans `0..width` × `0..height` in the chosen units. The same drawing
/// always gives the same bytes.
///
/// # Examples
///
/// ```
/// use crawltrace::stages::units::{PhysicalSize, Units};
/// use crawltrace::{to_dxf, CurvePath, Drawing, Point};
///
/// let triangle = [Point::new(0.0, 0.0), Point::new(96.0, 0.0), Point::new(0.0, 96.0)];
/// let drawing = Drawing {
///     width: 96.0,
///     height: 96.0,
///     paths: vec![CurvePath::polyline(&triangle, true)],
///     stroke_width: 2.0,
///     color: "black".into(),
///     dots: Vec::new(),
///     points: Vec::new(),
/// };
/// let dxf = to_dxf(&drawing, &PhysicalSize { dpi: 96.0, units: Units::Mm }, 0.5);
/// assert!(dxf.contains("LWPOLYLINE"));
/// assert!(dxf.ends_with("  0\nEOF\n"));
/// ```
pub fn to_dxf(drawing: &Drawing, size: &PhysicalSize, tolerance: f64) -> String {
    let mut writer = DxfWriter::default();
    let scale = size.units_per_pixel();
    let extent = Point::new(drawing.width * scale, drawing.height * scale);
    let to_dxf_point = |p: Point| Point::new(p.x * scale, (drawing.height - p.y) * scale);

    let owners = writer.tables(extent);
    writer.blocks(&owners);
    writer.section("ENTITIES");
    for path in &drawing.paths {
        let vertices: Vec<Point> = flatten_path(path, tolerance)
            .into_iter()
            .map(to_dxf_point)
            .collect();
        // A traced dot is a zero-length path (its size is its stroke width): CAD wants a POINT.
        match vertices.as_slice() {
            [] => {}
            [first, rest @ ..] if rest.iter().all(|p| p == first) => {
                writer.point(*first, owners.model_space)
            }
            _ => writer.lwpolyline(&vertices, path.closed, owners.model_space),
        }
    }
    for dot in &drawing.dots {
        writer.point(to_dxf_point(*dot), owners.model_space);
    }
    writer.end_section();
    writer.objects();
    writer.pair(0, "EOF");
    let body = std::mem::take(&mut writer.text);
    writer.header(size.units, extent);
    writer.text + &body
}

/// The handles of the records that other records point to.
struct Owners {
    /// `*Model_Space`'s block record: the owner of every entity.
    model_space: u32,
    /// `*Paper_Space`'s block record.
    paper_space: u32,
}

/// DXF text under construction, with the next free handle.
struct DxfWriter {
    text: String,
    next_handle: u32,
}

impl Default for DxfWriter {
    fn default() -> Self {
        Self {
            text: String::new(),
            // Handle 0 means "no owner"; real handles start at 1.
            next_handle: 1,
        }
    }
}

impl DxfWriter {
    /// A group code and its value, on two lines; codes right-aligned in three columns as
    /// AutoCAD writes them.
    fn pair(&mut self, code: i32, value: impl std::fmt::Display) {
        let _ = write!(self.text, "{code:>3}\n{value}\n");
    }

    /// A group code with a real number: fixed decimals, trailing zeros trimmed, at least one
    /// decimal, no `-0`.
    fn real(&mut self, code: i32, value: f64) {
        let mut text = format!("{value:.DECIMALS$}");
        let trimmed = text.trim_end_matches('0').len();
        text.truncate(trimmed);
        if text.ends_with('.') {
            text.push('0');
        }
        if text == "-0.0" {
            text = "0.0".to_string();
        }
        self.pair(code, text);
    }

    /// A 2D point as codes `10 + offset` and `20 + offset`.
    fn point_pair(&mut self, offset: i32, point: Point) {
        self.real(10 + offset, point.x);
        self.real(20 + offset, point.y);
    }

    /// A fresh handle, written with `code` (5 for most records, 105 for DIMSTYLE).
    fn handle(&mut self, code: i32) -> u32 {
        let handle = self.next_handle;
        self.next_handle += 1;
        self.pair(code, format!("{handle:X}"));
        handle
    }

    fn hex(&mut self, code: i32, handle: u32) {
        self.pair(code, format!("{handle:X}"));
    }

    fn section(&mut self, name: &str) {
        self.pair(0, "SECTION");
        self.pair(2, name);
    }

    fn end_section(&mut self) {
        self.pair(0, "ENDSEC");
    }

    /// The HEADER: version, handle seed, units, and the drawing's extents.
    fn header(&mut self, units: Units, extent: Point) {
        self.section("HEADER");
        self.pair(9, "$ACADVER");
        self.pair(1, "AC1015");
        self.pair(9, "$HANDSEED");
        let seed = self.next_handle;
        self.hex(5, seed);
        self.pair(9, "$INSUNITS");
        self.pair(
            70,
            match units {
                Units::Mm => INSUNITS_MILLIMETRES,
                Units::In => INSUNITS_INCHES,
            },
        );
        self.pair(9, "$MEASUREMENT");
        self.pair(70, i32::from(units == Units::Mm));
        self.pair(9, "$EXTMIN");
        self.point_pair(0, Point::ZERO);
        self.real(30, 0.0);
        self.pair(9, "$EXTMAX");
        self.point_pair(0, extent);
        self.real(30, 0.0);
        self.end_section();
    }

    /// The start of a table; returns its handle, the owner of its records.
    fn table(&mut self, name: &str, entries: i32) -> u32 {
        self.pair(0, "TABLE");
        self.pair(2, name);
        let handle = self.handle(5);
        self.pair(330, 0);
        self.pair(100, "AcDbSymbolTable");
        self.pair(70, entries);
        handle
    }

    /// The start of a table record of `kind` owned by `table`, with its subclass markers.
    fn record(&mut self, kind: &str, table: u32, subclass: &str, name: &str) -> u32 {
        self.pair(0, kind);
        let handle = self.handle(if kind == "DIMSTYLE" { 105 } else { 5 });
        self.hex(330, table);
        self.pair(100, "AcDbSymbolTableRecord");
        self.pair(100, subclass);
        self.pair(2, name);
        self.pair(70, 0);
        handle
    }

    fn end_table(&mut self) {
        self.pair(0, "ENDTAB");
    }

    /// The TABLES section with the entries every R13+ reader expects; the view opens on the
    /// drawing's extents.
    fn tables(&mut self, extent: Point) -> Owners {
        self.section("CLASSES");
        self.end_section();
        self.section("TABLES");
        self.viewport_table(extent);

        let table = self.table("LTYPE", 3);
        for name in ["ByBlock", "ByLayer", "Continuous"] {
            self.record("LTYPE", table, "AcDbLinetypeTableRecord", name);
            self.pair(
                3,
                if name == "Continuous" {
                    "Solid line"
                } else {
                    ""
                },
            );
            self.pair(72, 65);
            self.pair(73, 0);
            self.real(40, 0.0);
        }
        self.end_table();

        let table = self.table("LAYER", 1);
        self.record("LAYER", table, "AcDbLayerTableRecord", "0");
        self.pair(62, 7); // white on black screens, black on paper
        self.pair(6, "Continuous");
        self.end_table();

        let table = self.table("STYLE", 1);
        self.record("STYLE", table, "AcDbTextStyleTableRecord", "Standard");
        self.real(40, 0.0);
        self.real(41, 1.0);
        self.real(50, 0.0);
        self.pair(71, 0);
        self.real(42, 2.5);
        self.pair(3, "txt");
        self.pair(4, "");
        self.end_table();

        for empty in ["VIEW", "UCS"] {
            self.table(empty, 0);
            self.end_table();
        }

        let table = self.table("APPID", 1);
        self.record("APPID", table, "AcDbRegAppTableRecord", "ACAD");
        self.end_table();

        let table = self.table("DIMSTYLE", 1);
        self.pair(100, "AcDbDimStyleTable");
        self.record("DIMSTYLE", table, "AcDbDimStyleTableRecord", "Standard");
        self.end_table();

        let table = self.table("BLOCK_RECORD", 2);
        let model_space = self.record(
            "BLOCK_RECORD",
            table,
            "AcDbBlockTableRecord",
            "*Model_Space",
        );
        let paper_space = self.record(
            "BLOCK_RECORD",
            table,
            "AcDbBlockTableRecord",
            "*Paper_Space",
        );
        self.end_table();
        self.end_section();
        Owners {
            model_space,
            paper_space,
        }
    }

    /// The VPORT table: one `*ACTIVE` viewport centred on the drawing, showing all of it.
    fn viewport_table(&mut self, extent: Point) {
        let table = self.table("VPORT", 1);
        self.record("VPORT", table, "AcDbViewportTableRecord", "*ACTIVE");
        self.point_pair(0, Point::ZERO); // lower-left corner of the viewport on screen
        self.point_pair(1, Point::new(1.0, 1.0)); // upper-right corner
        self.point_pair(2, Point::new(extent.x / 2.0, extent.y / 2.0)); // view centre
        self.point_pair(3, Point::ZERO); // snap base
        self.point_pair(4, Point::new(10.0, 10.0)); // snap spacing
        self.point_pair(5, Point::new(10.0, 10.0)); // grid spacing
        self.point_pair(6, Point::ZERO); // view direction: straight down the z axis
        self.real(36, 1.0);
        self.point_pair(7, Point::ZERO); // view target
        self.real(37, 0.0);
        // The view is as tall as the drawing plus a margin, and as wide as the drawing is.
        let aspect = if extent.y > 0.0 {
            extent.x / extent.y
        } else {
            1.0
        };
        self.real(40, extent.y * (1.0 + 2.0 * VIEW_MARGIN_SHARE));
        self.real(41, aspect);
        self.real(42, 50.0); // lens length
        self.real(43, 0.0);
        self.real(44, 0.0);
        self.real(50, 0.0);
        self.real(51, 0.0);
        for (code, value) in [
            (71, 0),
            (72, 100),
            (73, 1),
            (74, 3),
            (75, 0),
            (76, 0),
            (77, 0),
            (78, 0),
        ] {
            self.pair(code, value);
        }
        self.end_table();
    }

    /// The BLOCKS section: the empty model and paper space blocks (their entities are in
    /// ENTITIES).
    fn blocks(&mut self, owners: &Owners) {
        self.section("BLOCKS");
        for (name, owner, paper) in [
            ("*Model_Space", owners.model_space, false),
            ("*Paper_Space", owners.paper_space, true),
        ] {
            self.entity(("BLOCK", "AcDbBlockBegin"), owner, paper);
            self.pair(2, name);
            self.pair(70, 0);
            self.point_pair(0, Point::ZERO);
            self.real(30, 0.0);
            self.pair(3, name);
            self.pair(1, "");
            self.entity(("ENDBLK", "AcDbBlockEnd"), owner, paper);
        }
        self.end_section();
    }

    /// The common start of an entity (or block marker) of `kind` and `subclass` on layer 0,
    /// owned by `owner`, in paper space if `paper_space`.
    fn entity(&mut self, (kind, subclass): (&str, &str), owner: u32, paper_space: bool) {
        self.pair(0, kind);
        self.handle(5);
        self.hex(330, owner);
        self.pair(100, "AcDbEntity");
        if paper_space {
            self.pair(67, 1);
        }
        self.pair(8, "0");
        self.pair(100, subclass);
    }

    fn lwpolyline(&mut self, vertices: &[Point], closed: bool, owner: u32) {
        self.entity(("LWPOLYLINE", "AcDbPolyline"), owner, false);
        self.pair(90, vertices.len());
        let closed = closed && vertices.len() > 2;
        self.pair(70, if closed { POLYLINE_CLOSED } else { 0 });
        self.real(43, 0.0); // constant width 0: a hairline, what cutters and plotters follow
        for vertex in vertices {
            self.point_pair(0, *vertex);
        }
    }

    fn point(&mut self, at: Point, owner: u32) {
        self.entity(("POINT", "AcDbPoint"), owner, false);
        self.point_pair(0, at);
        self.real(30, 0.0);
    }

    /// The OBJECTS section: the root dictionary and its one required entry, `ACAD_GROUP`.
    fn objects(&mut self) {
        self.section("OBJECTS");
        let root = self.next_handle;
        let group = root + 1;
        self.pair(0, "DICTIONARY");
        self.handle(5);
        self.pair(330, 0);
        self.pair(100, "AcDbDictionary");
        self.pair(281, 1);
        self.pair(3, "ACAD_GROUP");
        self.hex(350, group);
        self.pair(0, "DICTIONARY");
        self.handle(5);
        self.hex(330, root);
        self.pair(100, "AcDbDictionary");
        self.pair(281, 1);
        self.end_section();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::fit::CurvePath;

    fn drawing() -> Drawing {
        Drawing {
            width: 300.0,
            height: 150.0,
            paths: vec![
                CurvePath::polyline(
                    &[
                        Point::new(0.0, 0.0),
                        Point::new(300.0, 0.0),
                        Point::new(0.0, 150.0),
                    ],
                    true,
                ),
                CurvePath::polyline(&[Point::new(30.0, 30.0), Point::new(60.0, 90.0)], false),
                CurvePath::polyline(&[Point::new(5.0, 5.0)], false),
                CurvePath::dot(Point::new(20.0, 20.0), 6.0),
            ],
            stroke_width: 3.0,
            color: "black".into(),
            dots: vec![Point::new(150.0, 75.0)],
            points: vec![Point::new(1.0, 1.0)],
        }
    }

    /// The (code, value) pairs of a DXF text.
    fn pairs(dxf: &str) -> Vec<(i32, &str)> {
        let lines: Vec<&str> = dxf.lines().collect();
        assert_eq!(lines.len() % 2, 0);
        lines
            .chunks(2)
            .map(|pair| (pair[0].trim().parse().unwrap(), pair[1]))
            .collect()
    }

    #[test]
    fn every_curve_is_one_polyline_and_every_dot_a_point() {
        let size = PhysicalSize {
            dpi: 300.0,
            units: Units::Mm,
        };
        let dxf = to_dxf(&drawing(), &size, 0.5);
        let pairs = pairs(&dxf);
        let kinds: Vec<&str> = pairs
            .iter()
            .skip_while(|pair| **pair != (2, "ENTITIES"))
            .take_while(|pair| **pair != (0, "ENDSEC"))
            .filter(|(code, _)| *code == 0)
            .map(|(_, value)| *value)
            .collect();
        assert_eq!(
            kinds,
            ["LWPOLYLINE", "LWPOLYLINE", "POINT", "POINT", "POINT"]
        );
        let flags: Vec<&str> = pairs
            .windows(3)
            .filter(|w| w[0] == (100, "AcDbPolyline"))
            .map(|w| w[2].1)
            .collect();
        assert_eq!(flags, ["1", "0"]);
        // 300 px at 300 dpi is 25.4 mm; y points up, so the top-left pixel is at y = 12.7 mm.
        let triangle = "10\n0.0\n 20\n12.7\n 10\n25.4\n 20\n12.7\n 10\n0.0\n 20\n0.0\n";
        assert!(dxf.contains(triangle), "{dxf}");
        assert!(dxf.contains("$INSUNITS\n 70\n4\n"));
    }

    #[test]
    fn handles_are_unique_and_below_the_seed() {
        let dxf = to_dxf(&drawing(), &PhysicalSize::default(), 0.5);
        let pairs = pairs(&dxf);
        let handles: Vec<u32> = pairs
            .iter()
            .filter(|(code, _)| *code == 5 || *code == 105)
            .map(|(_, value)| u32::from_str_radix(value, 16).unwrap())
            .collect();
        let seed = handles[0]; // $HANDSEED is the first code-5 value, in the header
        let handles = &handles[1..];
        let unique: std::collections::BTreeSet<u32> = handles.iter().copied().collect();
        assert_eq!(unique.len(), handles.len());
        assert!(handles.iter().all(|&h| h > 0 && h < seed));
        assert_eq!(to_dxf(&drawing(), &PhysicalSize::default(), 0.5), dxf);
    }

    #[test]
    fn inches_are_declared_and_used() {
        let size = PhysicalSize {
            dpi: 100.0,
            units: Units::In,
        };
        let dxf = to_dxf(&drawing(), &size, 0.5);
        assert!(dxf.contains("$INSUNITS\n 70\n1\n"));
        assert!(dxf.contains("$EXTMAX\n 10\n3.0\n 20\n1.5\n"), "{dxf}");
    }
}
