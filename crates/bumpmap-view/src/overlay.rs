//! What the viewer draws over a rendered frame, into a layer of its own with straight alpha
//! (laid over the frame by `Rgba8Image::overlay` on the CPU, or by the window surface on the
//! GPU): text (the help, the status line, a message) from `font8x8`'s glyphs on a box that
//! darkens what is behind it, and the triangles' edges for the wireframe.
//!
//! What this module does not do: render (the frame comes from the renderer), or lay out more
//! than lines of text from the top-left or bottom-left corner.

use bumpmap::{Rgba8Image, Scene};
use font8x8::UnicodeFonts;
use glam::{Vec2, Vec4};

/// Where a block of text goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Corner {
    /// Lines from the top-left corner down.
    TopLeft,
    /// Lines ending at the bottom-left corner.
    BottomLeft,
}

/// The box behind text: black at three quarters, so what is behind shows at a quarter.
const BOX: [u8; 4] = [0, 0, 0, 192];

/// A layer of `width`×`height` with nothing on it.
pub fn layer(width: usize, height: usize) -> Rgba8Image {
    Rgba8Image::new(width, height, vec![[0; 4]; width * height])
}

/// Draws `lines` in white on a box that darkens what is behind it to a quarter, glyphs at up to
/// `max_scale` times their 8 pixels: the largest scale at which the box fits the layer. A line
/// too long for the layer's width even at the smallest scale is wrapped ([`wrap`]).
pub fn text(image: &mut Rgba8Image, lines: &[String], corner: Corner, max_scale: usize) {
    if lines.is_empty() {
        return;
    }
    let wrapped = wrap(lines, image.width.saturating_sub(8) / 8);
    let lines = wrapped.as_slice();
    let columns = lines.iter().map(|l| l.chars().count()).max().unwrap_or(0);
    let fits = |s: usize| (columns * 8 + 8) * s <= image.width && (lines.len() * 10 + 8) * s <= image.height;
    let scale = (1..=max_scale.max(1)).rev().find(|&s| fits(s)).unwrap_or(1);
    let (glyph, line_height, pad) = (8 * scale, 10 * scale, 4 * scale);
    let box_w = (columns * glyph + 2 * pad).min(image.width);
    let box_h = (lines.len() * line_height + 2 * pad).min(image.height);
    let top = match corner {
        Corner::TopLeft => 0,
        Corner::BottomLeft => image.height - box_h,
    };
    for y in top..top + box_h {
        for t in &mut image.texels[y * image.width..y * image.width + box_w] {
            if t[3] < BOX[3] {
                *t = BOX;
            }
        }
    }
    for (row, line) in lines.iter().enumerate() {
        for (col, ch) in line.chars().enumerate() {
            let Some(bits) = font8x8::BASIC_FONTS.get(ch).or_else(|| font8x8::LATIN_FONTS.get(ch)) else { continue };
            let (x0, y0) = (pad + col * glyph, top + pad + row * line_height);
            for (gy, byte) in bits.iter().enumerate() {
                for gx in 0..8 {
                    if byte >> gx & 1 == 0 {
                        continue;
                    }
                    for sy in 0..scale {
                        for sx in 0..scale {
                            let (x, y) = (x0 + gx * scale + sx, y0 + gy * scale + sy);
                            if x < image.width && y < image.height {
                                image.texels[y * image.width + x] = [255, 255, 255, 255];
                            }
                        }
                    }
                }
            }
        }
    }
}

/// `lines` with each longer than `columns` characters broken before its last `" | "` (else its
/// last space) that leaves the piece within `columns`, the continuations indented by two spaces;
/// a piece with neither is cut at `columns`.
pub fn wrap(lines: &[String], columns: usize) -> Vec<String> {
    let columns = columns.max(8);
    let mut out = Vec::new();
    for line in lines {
        let mut rest: Vec<char> = line.chars().collect();
        let mut indent = "";
        while indent.len() + rest.len() > columns {
            let room = columns - indent.len();
            let head: String = rest[..room].iter().collect();
            let cut = head.rfind(" | ").map(|i| (i, 3)).or_else(|| head.rfind(' ').map(|i| (i, 1)));
            let (end, skip) = match cut {
                Some((i, n)) if i > 0 => (head[..i].chars().count(), n),
                _ => (room, 0),
            };
            out.push(format!("{indent}{}", rest[..end].iter().collect::<String>()));
            rest.drain(..end + skip);
            indent = "  ";
        }
        out.push(format!("{indent}{}", rest.iter().collect::<String>()));
    }
    out
}

/// Draws the edges of the triangles of `scene`'s objects that face the camera, in green.
/// Triangles with a corner behind the eye are left out rather than clipped; hidden front faces
/// (behind another part of the object) are drawn, as there is no depth test here.
pub fn wireframe(image: &mut Rgba8Image, scene: &Scene) {
    let (w, h) = (image.width as f32, image.height as f32);
    let clip_from_world = scene.camera.clip_from_world(w / h);
    for object in &scene.objects {
        let clip_from_object = clip_from_world * object.world_from_object;
        let screen: Vec<Option<Vec2>> = object
            .mesh
            .positions
            .iter()
            .map(|p| {
                let c: Vec4 = clip_from_object * p.extend(1.0);
                (c.w > 1e-6).then(|| Vec2::new((c.x / c.w * 0.5 + 0.5) * w, (0.5 - c.y / c.w * 0.5) * h))
            })
            .collect();
        for tri in &object.mesh.indices {
            let corner = |i: u32| screen.get(i as usize).copied().flatten();
            let (Some(a), Some(b), Some(c)) = (corner(tri[0]), corner(tri[1]), corner(tri[2])) else { continue };
            // Counter-clockwise faces the eye (GL's default front face); on screen, whose y
            // runs down, that is a negative signed area.
            if (b - a).perp_dot(c - a) >= 0.0 {
                continue;
            }
            for (p, q) in [(a, b), (b, c), (c, a)] {
                line(image, p, q, [40, 255, 90, 255]);
            }
        }
    }
}

/// A one-pixel line from `a` to `b`, cut to the image.
fn line(image: &mut Rgba8Image, a: Vec2, b: Vec2, colour: [u8; 4]) {
    let (w, h) = (image.width as f32, image.height as f32);
    let outside = |p: Vec2| p.x < -w || p.x > 2.0 * w || p.y < -h || p.y > 2.0 * h;
    if outside(a) || outside(b) {
        return;
    }
    let steps = (b - a).abs().max_element().ceil().max(1.0) as usize;
    for i in 0..=steps {
        let p = a + (b - a) * (i as f32 / steps as f32);
        if p.x >= 0.0 && p.y >= 0.0 && p.x < w && p.y < h {
            image.texels[p.y as usize * image.width + p.x as usize] = colour;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_lights_pixels_in_its_corner_only() {
        let mut image = Rgba8Image::new(64, 48, vec![[100, 100, 100, 255]; 64 * 48]);
        let mut over = layer(64, 48);
        text(&mut over, &["Hi".into()], Corner::BottomLeft, 1);
        image.overlay(&over);
        let white = |y0: usize, y1: usize| {
            (y0..y1)
                .flat_map(|y| (0..64).map(move |x| (x, y)))
                .filter(|&(x, y)| image.texels[y * 64 + x][0] == 255)
                .count()
        };
        assert!(white(30, 48) > 10, "the glyphs are drawn at the bottom");
        assert_eq!(white(0, 30), 0, "nothing above the box");
        assert_eq!(image.texels[0], [100, 100, 100, 255], "outside the box is untouched");
        assert_eq!(image.texels[47 * 64][0], 25, "the box darkens to a quarter");
    }

    #[test]
    fn long_lines_wrap_between_fields() {
        let line = "pom | depth 0.1200 | layers 32 | torus | bumps 4.00".to_string();
        let wrapped = wrap(std::slice::from_ref(&line), 24);
        assert_eq!(wrapped, ["pom | depth 0.1200", "  layers 32 | torus", "  bumps 4.00"]);
        assert!(wrapped.iter().all(|l| l.chars().count() <= 24));
        // Short lines stay as they are; a word longer than the width is cut.
        assert_eq!(wrap(&["short".into()], 24), ["short"]);
        assert_eq!(wrap(&["abcdefghijkl".into()], 8), ["abcdefgh", "  ijkl"]);
    }
}
