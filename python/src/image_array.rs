//! A numpy array as an image for the tracer: `(H, W)` gray or `(H, W, C)` with 1 (gray), 2 (gray
//! and alpha), 3 (RGB) or 4 (RGBA) channels, of uint8 or uint16. Anything else is refused with a
//! message saying what was given and what is accepted.

use image::{DynamicImage, ImageBuffer, Luma, LumaA, Pixel, Rgb, Rgba};
use numpy::{
    dtype, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::error;

/// What the messages say is accepted.
const ACCEPTED: &str = "an image array must be (height, width) or (height, width, channels) with 1 to 4 channels, of uint8 or uint16";

/// The image held by `array` (copied).
pub fn to_image(array: &Bound<'_, PyUntypedArray>) -> PyResult<DynamicImage> {
    let py = array.py();
    let shape = array.shape().to_vec();
    let (height, width, channels) = match shape.as_slice() {
        [height, width] => (*height, *width, 1),
        [height, width, channels @ 1..=4] => (*height, *width, *channels),
        _ => return Err(error(format!("{ACCEPTED}; got shape {shape:?}"))),
    };
    if width == 0 || height == 0 {
        return Err(error(format!("empty image ({width}×{height} pixels)")));
    }
    let too_large = || error(format!("image array too large ({width}×{height} pixels)"));
    let width = u32::try_from(width).map_err(|_| too_large())?;
    let height = u32::try_from(height).map_err(|_| too_large())?;
    let element = array.dtype();
    if element.is_equiv_to(&dtype::<u8>(py)) {
        let samples = samples::<u8>(array)?;
        Ok(match channels {
            1 => DynamicImage::ImageLuma8(buffer::<Luma<u8>>(width, height, samples)?),
            2 => DynamicImage::ImageLumaA8(buffer::<LumaA<u8>>(width, height, samples)?),
            3 => DynamicImage::ImageRgb8(buffer::<Rgb<u8>>(width, height, samples)?),
            _ => DynamicImage::ImageRgba8(buffer::<Rgba<u8>>(width, height, samples)?),
        })
    } else if element.is_equiv_to(&dtype::<u16>(py)) {
        let samples = samples::<u16>(array)?;
        Ok(match channels {
            1 => DynamicImage::ImageLuma16(buffer::<Luma<u16>>(width, height, samples)?),
            2 => DynamicImage::ImageLumaA16(buffer::<LumaA<u16>>(width, height, samples)?),
            3 => DynamicImage::ImageRgb16(buffer::<Rgb<u16>>(width, height, samples)?),
            _ => DynamicImage::ImageRgba16(buffer::<Rgba<u16>>(width, height, samples)?),
        })
    } else {
        Err(error(format!("{ACCEPTED}; got dtype {element}")))
    }
}

/// The array's elements in row-major order, whatever its memory layout.
fn samples<T: numpy::Element + Copy>(array: &Bound<'_, PyUntypedArray>) -> PyResult<Vec<T>> {
    let typed = array.cast::<PyArrayDyn<T>>()?;
    let readonly = typed.try_readonly().map_err(|e| error(e.to_string()))?;
    Ok(readonly.as_array().iter().copied().collect())
}

/// An image buffer of `width` × `height` pixels from their samples.
fn buffer<P: Pixel>(
    width: u32,
    height: u32,
    samples: Vec<P::Subpixel>,
) -> PyResult<ImageBuffer<P, Vec<P::Subpixel>>> {
    ImageBuffer::from_raw(width, height, samples)
        .ok_or_else(|| error("the image array's size does not match its shape"))
}
