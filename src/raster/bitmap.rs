//! A packed-free binary image (one byte a pixel, 1 = ink) shared by the raster stages, with the
//! `#`/`.` grid literals the unit tests are written in (the imageproc style).

use crate::geometry::floor_to_i64;

/// A binary image: `true` pixels are ink (or skeleton).
#[derive(Clone, PartialEq, Eq)]
pub struct Bitmap {
    width: usize,
    height: usize,
    pixels: Vec<u8>,
}

impl Bitmap {
    /// An all-background bitmap.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            pixels: vec![0; width * height],
        }
    }

    /// A bitmap of `pixels`, row by row (0 background, 1 ink). Panics unless there are
    /// `width * height` of them.
    pub(crate) fn from_pixels(width: usize, height: usize, pixels: Vec<u8>) -> Self {
        assert_eq!(
            pixels.len(),
            width * height,
            "a bitmap's pixels fill its rows"
        );
        Self {
            width,
            height,
            pixels,
        }
    }

    /// The `width` by `height` window of this bitmap whose top left pixel is (`x0`, `y0`);
    /// pixels past the edge are background.
    pub(crate) fn crop(&self, x0: usize, y0: usize, width: usize, height: usize) -> Self {
        let mut window = Self::new(width, height);
        let columns = width.min(self.width.saturating_sub(x0));
        for y in 0..height.min(self.height.saturating_sub(y0)) {
            let from = (y0 + y) * self.width + x0;
            window.pixels[y * width..y * width + columns]
                .copy_from_slice(&self.pixels[from..from + columns]);
        }
        window
    }

    /// Parses a grid literal: one row a line, `#` for ink, `.` for background; blank lines and
    /// surrounding white space are ignored. Panics on ragged rows (it is for tests and fixtures).
    pub fn from_grid(grid: &str) -> Self {
        let rows: Vec<&str> = grid
            .lines()
            .map(str::trim)
            .filter(|row| !row.is_empty())
            .collect();
        let width = rows.first().map_or(0, |row| row.chars().count());
        let mut bitmap = Self::new(width, rows.len());
        for (y, row) in rows.iter().enumerate() {
            assert_eq!(row.chars().count(), width, "ragged grid row {y}: {row:?}");
            for (x, c) in row.chars().enumerate() {
                bitmap.set(x, y, c == '#');
            }
        }
        bitmap
    }

    /// The bitmap as a grid literal (see [`Self::from_grid`]).
    pub fn to_grid(&self) -> String {
        let mut grid = String::with_capacity((self.width + 1) * self.height);
        for y in 0..self.height {
            for x in 0..self.width {
                grid.push(if self.get(x, y) { '#' } else { '.' });
            }
            grid.push('\n');
        }
        grid
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Whether (x, y) is ink. Panics outside the bitmap.
    #[inline]
    pub fn get(&self, x: usize, y: usize) -> bool {
        self.pixels[y * self.width + x] != 0
    }

    /// Whether (x, y) is ink; `false` outside the bitmap.
    #[inline]
    pub fn get_signed(&self, x: isize, y: isize) -> bool {
        x >= 0
            && y >= 0
            && (x as usize) < self.width
            && (y as usize) < self.height
            && self.pixels[y as usize * self.width + x as usize] != 0
    }

    /// The width of ink across `point` along the unit vector `normal`, counted in steps of
    /// `step` pixels up to `reach` to either side; 0 when `point` is off the ink. Used to tell
    /// a band of two merged strokes from one stroke.
    pub(crate) fn ink_across(
        &self,
        point: kurbo::Point,
        normal: kurbo::Vec2,
        step: f64,
        reach: f64,
    ) -> f64 {
        let ink = |q: kurbo::Point| {
            self.get_signed(floor_to_i64(q.x) as isize, floor_to_i64(q.y) as isize)
        };
        if !ink(point) {
            return 0.0;
        }
        let mut width = step;
        for sign in [1.0, -1.0] {
            let mut t = step;
            while t < reach && ink(point + normal * (sign * t)) {
                t += step;
                width += step;
            }
        }
        width
    }

    /// Sets (x, y) to ink or background. Panics outside the bitmap.
    #[inline]
    pub fn set(&mut self, x: usize, y: usize, ink: bool) {
        self.pixels[y * self.width + x] = u8::from(ink);
    }

    /// One byte a pixel, row by row, 1 for ink.
    pub fn as_bytes(&self) -> &[u8] {
        &self.pixels
    }

    /// Mutable access to the bytes of [`Self::as_bytes`]; keep them 0 or 1.
    pub fn as_bytes_mut(&mut self) -> &mut [u8] {
        &mut self.pixels
    }

    /// Number of ink pixels.
    pub fn count_ink(&self) -> usize {
        self.pixels.iter().filter(|&&p| p != 0).count()
    }

    /// Whether any pixel is ink: [`Self::count_ink`] `> 0`, but it stops at the first ink pixel
    /// instead of reading the whole bitmap (a 12-megapixel page: 57 M instructions to count).
    pub fn has_ink(&self) -> bool {
        self.pixels.iter().any(|&p| p != 0)
    }

    /// The 8 neighbours of (x, y) as a bit mask, bit k set when neighbour k is ink, counting
    /// clockwise from north: 0 N, 1 NE, 2 E, 3 SE, 4 S, 5 SW, 6 W, 7 NW. Outside counts as
    /// background.
    #[inline]
    pub fn neighbourhood(&self, x: usize, y: usize) -> u8 {
        let (x, y) = (x as isize, y as isize);
        let mut mask = 0u8;
        for (k, (dx, dy)) in NEIGHBOUR_OFFSETS.iter().enumerate() {
            if self.get_signed(x + dx, y + dy) {
                mask |= 1 << k;
            }
        }
        mask
    }
}

/// Offsets of the 8 neighbours, clockwise from north (y grows downwards), matching the bits of
/// [`Bitmap::neighbourhood`].
pub const NEIGHBOUR_OFFSETS: [(isize, isize); 8] = [
    (0, -1),
    (1, -1),
    (1, 0),
    (1, 1),
    (0, 1),
    (-1, 1),
    (-1, 0),
    (-1, -1),
];

impl std::fmt::Debug for Bitmap {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "Bitmap {}×{}", self.width, self.height)?;
        f.write_str(&self.to_grid())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_window_keeps_its_pixels_and_is_blank_past_the_edge() {
        let bitmap = Bitmap::from_grid(
            "
            #..
            .#.
            ..#
            ",
        );
        let window = bitmap.crop(1, 1, 3, 2);
        assert_eq!(window.to_grid(), Bitmap::from_grid("#..\n.#.").to_grid());
        assert_eq!(bitmap.crop(0, 0, 3, 3), bitmap);
        assert!(!bitmap.crop(3, 3, 2, 2).has_ink());
    }

    #[test]
    fn has_ink_as_the_count_says() {
        let mut bitmap = Bitmap::new(40, 30);
        assert!(!bitmap.has_ink());
        bitmap.set(39, 29, true);
        assert!(bitmap.has_ink());
        assert_eq!(bitmap.has_ink(), bitmap.count_ink() > 0);
        bitmap.set(39, 29, false);
        bitmap.set(0, 0, true);
        assert!(bitmap.has_ink());
    }

    #[test]
    fn grid_round_trip_and_neighbourhood_bits() {
        let grid = "#..\n.#.\n..#\n";
        let bitmap = Bitmap::from_grid(grid);
        assert_eq!(bitmap.to_grid(), grid);
        assert_eq!(
            (bitmap.width(), bitmap.height(), bitmap.count_ink()),
            (3, 3, 3)
        );
        // Centre pixel: NW (bit 7) and SE (bit 3) are ink.
        assert_eq!(bitmap.neighbourhood(1, 1), (1 << 7) | (1 << 3));
        assert_eq!(bitmap.neighbourhood(0, 0), 1 << 3);
    }
}
