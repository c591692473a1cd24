//! A 3 x 5 pixel digit font for the frame numbers on the contact sheet's tiles.

/// Rows of the digits 0-9, top to bottom, 3 bits each (bit 2 is the left column).
const DIGITS: [[u8; 5]; 10] = [
    [0b111, 0b101, 0b101, 0b101, 0b111],
    [0b010, 0b110, 0b010, 0b010, 0b111],
    [0b111, 0b001, 0b111, 0b100, 0b111],
    [0b111, 0b001, 0b111, 0b001, 0b111],
    [0b101, 0b101, 0b111, 0b001, 0b001],
    [0b111, 0b100, 0b111, 0b001, 0b111],
    [0b111, 0b100, 0b111, 0b101, 0b111],
    [0b111, 0b001, 0b001, 0b001, 0b001],
    [0b111, 0b101, 0b111, 0b101, 0b111],
    [0b111, 0b101, 0b111, 0b001, 0b111],
];

/// Draws the decimal `number` into the RGBA8 image `rgba` (`width` pixels wide) with its
/// top-left corner at `at`, each font pixel `scale` x `scale` image pixels, in `ink` on a
/// `paper` box one font pixel wider on every side. Pixels outside the image are skipped.
pub fn draw_number(
    rgba: &mut [u8],
    width: usize,
    at: [usize; 2],
    number: u32,
    scale: usize,
    ink: [u8; 3],
    paper: [u8; 3],
) {
    let text = number.to_string();
    let glyphs: Vec<usize> = text
        .bytes()
        .map(|b| usize::from(b.saturating_sub(b'0')).min(9))
        .collect();
    let height = rgba.len() / 4 / width.max(1);
    let columns = 4 * glyphs.len() + 1; // 3 columns + 1 gap per glyph, plus the box border
    let mut put = |fx: usize, fy: usize, colour: [u8; 3]| {
        for dy in 0..scale {
            for dx in 0..scale {
                let (x, y) = (at[0] + fx * scale + dx, at[1] + fy * scale + dy);
                if x < width && y < height {
                    let k = 4 * (y * width + x);
                    rgba[k..k + 3].copy_from_slice(&colour);
                    rgba[k + 3] = 255;
                }
            }
        }
    };
    for fy in 0..7 {
        for fx in 0..columns {
            put(fx, fy, paper);
        }
    }
    for (g, &digit) in glyphs.iter().enumerate() {
        for (row, bits) in DIGITS[digit].iter().enumerate() {
            for col in 0..3 {
                if bits >> (2 - col) & 1 == 1 {
                    put(1 + 4 * g + col, 1 + row, ink);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_inside_and_clips_outside() {
        let mut img = vec![0u8; 4 * 20 * 10];
        draw_number(&mut img, 20, [1, 1], 1, 1, [255, 0, 0], [0, 0, 255]);
        // "1": the box is 5 x 7 from (1, 1); the top row of the glyph has its middle set.
        let px = |x: usize, y: usize| &img[4 * (y * 20 + x)..4 * (y * 20 + x) + 3];
        assert_eq!(px(1, 1), [0, 0, 255]);
        assert_eq!(px(3, 2), [255, 0, 0]);
        assert_eq!(px(2, 2), [0, 0, 255]);
        assert_eq!(px(0, 0), [0, 0, 0]);
        // Far outside: nothing drawn, no panic.
        draw_number(&mut img, 20, [18, 8], u32::MAX, 3, [1, 1, 1], [2, 2, 2]);
        draw_number(&mut img, 0, [0, 0], 7, 1, [1, 1, 1], [2, 2, 2]);
    }
}
