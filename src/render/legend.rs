//! The legend of `lrmesh render`: a band below the picture with the ring-order colour ramp
//! or the triangle-class swatches, labelled in a built-in 5 × 7 pixel font, so that a
//! picture explains itself without the command's help.

use super::colors::{blue_to_red, class_color};
use super::{ColorMode, Image};
use crate::lr::TriangleClass;

/// Glyphs of the labels, 5 columns × 7 rows, a row's bit 4 the leftmost pixel.
const GLYPHS: &[(char, [u8; 7])] = &[
    (' ', [0, 0, 0, 0, 0, 0, 0]),
    ('0', [14, 17, 19, 21, 25, 17, 14]),
    ('1', [4, 12, 4, 4, 4, 4, 14]),
    ('2', [14, 17, 1, 2, 4, 8, 31]),
    ('T', [31, 4, 4, 4, 4, 4, 4]),
    ('a', [0, 0, 14, 1, 15, 17, 15]),
    ('b', [16, 16, 22, 25, 17, 17, 30]),
    ('d', [1, 1, 13, 19, 17, 17, 15]),
    ('e', [0, 0, 14, 17, 31, 16, 14]),
    ('f', [6, 9, 8, 28, 8, 8, 8]),
    ('g', [0, 15, 17, 17, 15, 1, 14]),
    ('h', [16, 16, 22, 25, 17, 17, 17]),
    ('i', [4, 0, 12, 4, 4, 4, 14]),
    ('k', [16, 16, 18, 20, 24, 20, 18]),
    ('l', [12, 4, 4, 4, 4, 4, 14]),
    ('n', [0, 0, 22, 25, 17, 17, 17]),
    ('o', [0, 0, 14, 17, 17, 17, 14]),
    ('p', [0, 0, 30, 17, 30, 16, 16]),
    ('r', [0, 0, 22, 25, 16, 16, 16]),
    ('s', [0, 0, 14, 16, 14, 1, 30]),
    ('t', [8, 8, 28, 8, 8, 9, 6]),
    ('w', [0, 0, 17, 17, 21, 21, 10]),
];

/// The height of the band [`with_legend`] adds below a picture `width` pixels wide.
pub fn legend_height(width: u32) -> u32 {
    9 * font_scale(width) + 8
}

/// Pixels per font pixel: 2 from 500 pixels wide.
fn font_scale(width: u32) -> u32 {
    if width >= 500 {
        2
    } else {
        1
    }
}

/// `image` with a legend band below it for `mode` ([`legend_height`] pixels).
pub fn with_legend(image: &Image, mode: ColorMode) -> Image {
    let scale = font_scale(image.width);
    let band = legend_height(image.width);
    let (width, height) = (image.width, image.height + band);
    let mut out = Image {
        width,
        height,
        rgb: vec![255; (width * height * 3) as usize],
    };
    out.rgb[..image.rgb.len()].copy_from_slice(&image.rgb);
    let mut pen = Pen {
        image: &mut out,
        x: 4,
        top: image.height + 4,
        scale,
    };
    pen.rule(image.height);
    let to_u8 = |c: [f32; 3]| c.map(|x| (255.0 * x).round().clamp(0.0, 254.0) as u8);
    match mode {
        ColorMode::Ring => {
            pen.text("ring start ");
            let bar = 60 * scale;
            for i in 0..bar {
                let color = to_u8(blue_to_red(i as f32 / (bar - 1) as f32));
                pen.fill(pen.x + i, 1, 7 * scale, color);
            }
            pen.x += bar;
            pen.text(" end   ");
            pen.swatch(to_u8([0.6, 0.6, 0.6]));
            pen.text("off the ring");
        }
        ColorMode::Classes => {
            for (class, name) in [
                (TriangleClass::T1Left, "T1 left  "),
                (TriangleClass::T1Right, "T1 right  "),
                (TriangleClass::T2, "T2  "),
                (TriangleClass::T2Wart, "T2 wart  "),
                (TriangleClass::T0, "T0  "),
                (TriangleClass::T0Wart, "T0 wart"),
            ] {
                pen.swatch(to_u8(class_color(class)));
                pen.text(name);
            }
        }
    }
    out
}

/// Where the next mark of the legend goes.
struct Pen<'a> {
    image: &'a mut Image,
    x: u32,
    top: u32,
    scale: u32,
}

impl Pen<'_> {
    fn set(&mut self, x: u32, y: u32, color: [u8; 3]) {
        if x < self.image.width && y < self.image.height {
            let i = 3 * (y * self.image.width + x) as usize;
            self.image.rgb[i..i + 3].copy_from_slice(&color);
        }
    }

    /// A block `width` wide, rows `from` to `from + rows` of the text line (in pixels).
    fn fill(&mut self, x: u32, from: u32, rows: u32, color: [u8; 3]) {
        for dy in 0..rows {
            self.set(x, self.top + from + dy, color);
        }
    }

    /// A grey line across the picture's bottom edge at row `y`.
    fn rule(&mut self, y: u32) {
        for x in 0..self.image.width {
            self.set(x, y, [200, 200, 200]);
        }
    }

    /// A square of `color` with a dark outline, then a space.
    fn swatch(&mut self, color: [u8; 3]) {
        let side = 7 * self.scale;
        for dx in 0..side {
            let edge = dx == 0 || dx + 1 == side;
            for dy in 0..side {
                let c = if edge || dy == 0 || dy + 1 == side {
                    [60, 60, 60]
                } else {
                    color
                };
                self.set(self.x + dx, self.top + dy, c);
            }
        }
        self.x += side + 3 * self.scale;
    }

    /// `text` in the built-in font (unknown characters as spaces).
    fn text(&mut self, text: &str) {
        for ch in text.chars() {
            let rows = GLYPHS
                .iter()
                .find(|(c, _)| *c == ch)
                .map_or([0; 7], |(_, rows)| *rows);
            for (row, bits) in rows.iter().enumerate() {
                for col in 0..5 {
                    if bits >> (4 - col) & 1 == 1 {
                        let s = self.scale;
                        for (sx, sy) in (0..s).flat_map(|a| (0..s).map(move |b| (a, b))) {
                            let x = self.x + col * s + sx;
                            let y = self.top + row as u32 * s + sy;
                            self.set(x, y, [30, 30, 30]);
                        }
                    }
                }
            }
            self.x += 6 * self.scale;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_band_holds_the_ramp_and_the_picture_stays() {
        let picture = Image {
            width: 600,
            height: 40,
            rgb: vec![7; 600 * 40 * 3],
        };
        let ring = with_legend(&picture, ColorMode::Ring);
        assert!(ring.height > picture.height);
        assert_eq!(&ring.rgb[..picture.rgb.len()], &picture.rgb[..]);
        let band: Vec<[u8; 3]> = (picture.height + 1..ring.height)
            .flat_map(|y| (0..ring.width).map(move |x| (x, y)))
            .filter_map(|(x, y)| ring.pixel(x, y))
            .collect();
        let blue = band.iter().any(|p| p[2] > 200 && p[0] < 60);
        let red = band.iter().any(|p| p[0] > 200 && p[2] < 60);
        let ink = band.iter().filter(|&&p| p == [30, 30, 30]).count();
        assert!(blue && red && ink > 100, "{blue} {red} {ink}");
        let classes = with_legend(&picture, ColorMode::Classes);
        let green = to_band(&classes, picture.height)
            .iter()
            .any(|p| p[1] > 150 && p[0] < 60 && p[2] < 100);
        assert!(green);
    }

    fn to_band(image: &Image, from: u32) -> Vec<[u8; 3]> {
        (from..image.height)
            .flat_map(|y| (0..image.width).map(move |x| (x, y)))
            .filter_map(|(x, y)| image.pixel(x, y))
            .collect()
    }
}
