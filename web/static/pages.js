// Page textures drawn on a canvas: paper, a text block of lines inside margins, a heading
// on a recto and a figure on a verso (so the two sides are told apart, as on the contact
// sheet), and the page number at the foot's outer corner. Canvas (u, v): u left to right as
// the side is read, v from the head down, as the page mesh lays out its texture coordinates.

const PAPER = '#f6f3ec';
const INK = '#38383f';
const FIGURE = '#8fa6bd';
const WORDS = ('the page bends and turns like paper a sheet is a surface that does not ' +
  'stretch so it curls into cones and cylinders where it is held the book keeps its ' +
  'blocks of pages on either side of the spine and each turn moves one leaf from the ' +
  'right to the left').split(' ');

// A small deterministic generator (an integer hash), so a page number always gets the
// same text.
function generator(seed) {
  let x = (seed * 2654435761) >>> 0;
  return () => {
    x ^= x << 13; x >>>= 0;
    x ^= x >>> 17;
    x ^= x << 5; x >>>= 0;
    return x / 4294967296;
  };
}

// Draws page `number` (1 is the first recto) into `canvas`.
export function drawPage(canvas, number) {
  const ctx = canvas.getContext('2d');
  const w = canvas.width, h = canvas.height;
  const recto = number % 2 === 1;
  const random = generator(number + 1);
  ctx.fillStyle = PAPER;
  ctx.fillRect(0, 0, w, h);
  const margin = 0.11 * w;
  const inner = recto ? 1.4 * margin : margin;
  const left = inner, right = w - (recto ? margin : 1.4 * margin);
  const lineHeight = h / 38;
  ctx.fillStyle = INK;
  ctx.textBaseline = 'alphabetic';
  let y = 1.3 * margin;
  if (recto) {
    ctx.font = `bold ${Math.round(1.9 * lineHeight)}px serif`;
    ctx.fillText(`Chapter ${Math.ceil(number / 12)}`, left, y + 1.5 * lineHeight);
    y += 3.5 * lineHeight;
  } else {
    ctx.fillStyle = FIGURE;
    const fh = 9 * lineHeight;
    ctx.fillRect(left, y, right - left, fh);
    ctx.fillStyle = INK;
    ctx.font = `italic ${Math.round(0.8 * lineHeight)}px serif`;
    ctx.fillText(`Figure ${number / 2}: a page in flight.`, left, y + fh + 1.2 * lineHeight);
    y += fh + 2.6 * lineHeight;
  }
  ctx.font = `${Math.round(0.72 * lineHeight)}px serif`;
  const bottom = h - 1.6 * margin;
  let line = 0;
  while (y < bottom) {
    const paragraphEnd = line % 7 === 6;
    let x = left + (line % 7 === 0 ? 2 * lineHeight : 0);
    const end = paragraphEnd ? left + (0.3 + 0.5 * random()) * (right - left) : right;
    while (true) {
      const word = WORDS[Math.floor(random() * WORDS.length)];
      const width = ctx.measureText(word).width;
      if (x + width > end) break;
      ctx.fillText(word, x, y);
      x += width + 0.32 * lineHeight;
    }
    y += lineHeight;
    line += 1;
  }
  ctx.font = `${Math.round(0.8 * lineHeight)}px serif`;
  ctx.textAlign = recto ? 'right' : 'left';
  ctx.fillText(String(number), recto ? right : left, h - 0.9 * margin);
  ctx.textAlign = 'left';
}

// The page numbers on view for a book with `left`, `right` and `active` pages (sheets):
// sheet s carries pages 2s - 1 (recto) and 2s (verso); the left block's top shows the verso
// of its last sheet, the held stack its first recto and last verso, the right block's top
// the recto of the sheet after them. 0 where there is no such page.
export function pagesOnView(left, right, active) {
  return {
    front: active > 0 ? 2 * left + 1 : 0,
    back: active > 0 ? 2 * (left + active) : 0,
    leftTop: left > 0 ? 2 * left : 0,
    rightTop: right > 0 ? 2 * (left + active) + 1 : 0,
  };
}
