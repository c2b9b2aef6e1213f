//! Physical size of an output: how many pixels make an inch (`--dpi`, or the image's own
//! density, or `--size` on the longer side), and whether lengths are written in millimetres or
//! inches (`--units`). The SVG writer uses it for `width`/`height` (the `viewBox` stays in
//! pixels); the DXF writer scales every coordinate by it.

use std::fmt;
use std::str::FromStr;

/// Millimetres in an inch (exact, by definition).
pub const MM_PER_INCH: f64 = 25.4;

/// DECISION: without `--dpi`, `--size` or a density in the image file, a pixel is a CSS pixel,
/// 1/96 inch: what browsers, Inkscape and vpype take, so the SVG shows at the size it always had.
pub const DEFAULT_DPI: f64 = 96.0;

/// The unit lengths are written in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Units {
    /// Millimetres (the default: laser and CNC software mostly works in mm).
    #[default]
    Mm,
    /// Inches.
    In,
}

impl Units {
    /// The unit's name as SVG and the command line write it: `mm` or `in`.
    pub fn name(self) -> &'static str {
        match self {
            Units::Mm => "mm",
            Units::In => "in",
        }
    }

    /// How many of this unit make an inch.
    pub fn per_inch(self) -> f64 {
        match self {
            Units::Mm => MM_PER_INCH,
            Units::In => 1.0,
        }
    }
}

impl fmt::Display for Units {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a unit or a length was refused; one line, for a user.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum UnitsError {
    /// Not `mm` or `in`.
    #[error("must be mm or in")]
    UnknownUnit,
    /// Not a positive length with a unit.
    #[error("must be a positive length with a unit, such as 210mm, 21cm or 8in")]
    NotALength,
}

impl FromStr for Units {
    type Err = UnitsError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        match text.trim().to_ascii_lowercase().as_str() {
            "mm" => Ok(Units::Mm),
            "in" => Ok(Units::In),
            _ => Err(UnitsError::UnknownUnit),
        }
    }
}

/// A physical length such as `210mm`, `21cm` or `8in` (`--size`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Length {
    /// The length in inches.
    pub inches: f64,
    /// The unit it was given in (centimetres count as millimetres), the natural unit to write
    /// the output in when none is asked for.
    pub units: Units,
}

impl FromStr for Length {
    type Err = UnitsError;

    /// Parses a positive finite number followed by `mm`, `cm` or `in` (any letter case, spaces
    /// allowed between them).
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let text = text.trim().to_ascii_lowercase();
        let (number, units, per_inch) = if let Some(number) = text.strip_suffix("mm") {
            (number, Units::Mm, MM_PER_INCH)
        } else if let Some(number) = text.strip_suffix("cm") {
            (number, Units::Mm, MM_PER_INCH / 10.0)
        } else if let Some(number) = text.strip_suffix("in") {
            (number, Units::In, 1.0)
        } else {
            return Err(UnitsError::NotALength);
        };
        let value: f64 = number.trim().parse().map_err(|_| UnitsError::NotALength)?;
        let inches = value / per_inch;
        if inches.is_finite() && inches > 0.0 {
            Ok(Length { inches, units })
        } else {
            Err(UnitsError::NotALength)
        }
    }
}

/// The physical size of a drawing's pixels, and the unit to write lengths in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhysicalSize {
    /// Pixels per inch; finite and positive.
    pub dpi: f64,
    /// The unit lengths are written in.
    pub units: Units,
}

impl Default for PhysicalSize {
    /// [`DEFAULT_DPI`] in millimetres.
    fn default() -> Self {
        Self {
            dpi: DEFAULT_DPI,
            units: Units::Mm,
        }
    }
}

impl PhysicalSize {
    /// How long `pixels` pixels are, in [`Self::units`].
    pub fn length(&self, pixels: f64) -> f64 {
        pixels * self.units_per_pixel()
    }

    /// How many [`Self::units`] a pixel is.
    pub fn units_per_pixel(&self) -> f64 {
        self.units.per_inch() / self.dpi
    }
}

/// What a user asked for about the physical size; [`SizeRequest::resolve`] turns it into a
/// [`PhysicalSize`] for one drawing. `Default` asks for nothing: the image's own density, else
/// [`DEFAULT_DPI`], in millimetres.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SizeRequest {
    /// `--dpi`: pixels per inch, overriding the image's own density.
    pub dpi: Option<f64>,
    /// `--size`: the length of the drawing's longer side; overrides every density.
    pub size: Option<Length>,
    /// `--units`: the unit to write; by default the unit of `size`, else millimetres.
    pub units: Option<Units>,
}

/// Why a [`SizeRequest`] is refused by [`SizeRequest::check`]; one line, for a user.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SizeRequestError {
    /// `dpi` is zero, negative, infinite or NaN.
    #[error("--dpi must be a positive number")]
    BadDpi,
}

impl SizeRequest {
    /// Refuses a `dpi` that is not a positive finite number (which [`Self::resolve`] would
    /// ignore), for front ends that report bad input instead of ignoring it.
    ///
    /// # Errors
    ///
    /// [`SizeRequestError::BadDpi`].
    pub fn check(&self) -> Result<(), SizeRequestError> {
        match self.dpi {
            Some(dpi) if !(dpi.is_finite() && dpi > 0.0) => Err(SizeRequestError::BadDpi),
            _ => Ok(()),
        }
    }

    /// The physical size of a drawing of `width` × `height` pixels whose image file recorded
    /// `image_dpi` (if any). Priority: `size`, then `dpi`, then `image_dpi`, then
    /// [`DEFAULT_DPI`]; a density that is not a positive finite number counts as absent.
    pub fn resolve(&self, width: f64, height: f64, image_dpi: Option<f64>) -> PhysicalSize {
        let usable = |dpi: &f64| dpi.is_finite() && *dpi > 0.0;
        let longer_side = width.max(height);
        let from_size = self
            .size
            .map(|size| longer_side / size.inches)
            .filter(usable);
        let dpi = from_size
            .or(self.dpi.filter(usable))
            .or(image_dpi.filter(usable))
            .unwrap_or(DEFAULT_DPI);
        let units = self
            .units
            .or(self.size.map(|size| size.units))
            .unwrap_or_default();
        PhysicalSize { dpi, units }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_need_a_positive_number_and_a_unit() {
        let length = |text: &str| text.parse::<Length>();
        assert_eq!(length("254mm").unwrap().inches, 10.0);
        assert_eq!(length("25.4 cm").unwrap().inches, 10.0);
        assert_eq!(length("8IN").unwrap().units, Units::In);
        assert_eq!(length("21cm").unwrap().units, Units::Mm);
        for bad in [
            "banana", "210", "mm", "-5mm", "0in", "infmm", "NaNin", "", "1e400mm",
        ] {
            assert_eq!(length(bad), Err(UnitsError::NotALength), "{bad:?}");
        }
        assert_eq!("in".parse::<Units>(), Ok(Units::In));
        assert_eq!("cm".parse::<Units>(), Err(UnitsError::UnknownUnit));
    }

    #[test]
    fn size_wins_over_dpi_which_wins_over_the_image_density() {
        let (width, height) = (3000.0, 2000.0);
        let nothing = SizeRequest::default();
        assert_eq!(
            nothing.resolve(width, height, None),
            PhysicalSize::default()
        );
        assert_eq!(nothing.resolve(width, height, Some(300.0)).dpi, 300.0);

        let dpi = SizeRequest {
            dpi: Some(600.0),
            ..SizeRequest::default()
        };
        assert_eq!(dpi.resolve(width, height, Some(300.0)).dpi, 600.0);

        let size = SizeRequest {
            dpi: Some(600.0),
            size: Some("10in".parse().unwrap()),
            units: None,
        };
        let resolved = size.resolve(width, height, Some(300.0));
        assert_eq!(resolved.dpi, 300.0); // 3000 px on 10 in
        assert_eq!(resolved.units, Units::In); // the unit of --size
        assert_eq!(resolved.length(width), 10.0);

        let tall = SizeRequest {
            size: Some("100mm".parse().unwrap()),
            units: Some(Units::In),
            ..SizeRequest::default()
        };
        let resolved = tall.resolve(500.0, 1000.0, None);
        assert!((resolved.length(1000.0) - 100.0 / MM_PER_INCH).abs() < 1e-12);
        assert_eq!(resolved.units, Units::In);
    }

    #[test]
    fn a_bad_dpi_or_image_density_is_refused_or_ignored() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let request = SizeRequest {
                dpi: Some(bad),
                ..SizeRequest::default()
            };
            assert_eq!(request.check(), Err(SizeRequestError::BadDpi));
            assert_eq!(request.resolve(10.0, 10.0, None).dpi, DEFAULT_DPI);
            let from_image = SizeRequest::default().resolve(10.0, 10.0, Some(bad));
            assert_eq!(from_image.dpi, DEFAULT_DPI);
        }
        assert_eq!(SizeRequest::default().check(), Ok(()));
        // An empty drawing has no longer side to scale: the size falls back to the density.
        let size = SizeRequest {
            size: Some("1in".parse().unwrap()),
            ..SizeRequest::default()
        };
        assert_eq!(size.resolve(0.0, 0.0, Some(200.0)).dpi, 200.0);
    }

    #[test]
    fn millimetres_and_inches_convert_exactly() {
        let size = PhysicalSize {
            dpi: 300.0,
            units: Units::Mm,
        };
        assert!((size.length(300.0) - 25.4).abs() < 1e-12);
        let size = PhysicalSize {
            dpi: 300.0,
            units: Units::In,
        };
        assert_eq!(size.length(600.0), 2.0);
    }
}
