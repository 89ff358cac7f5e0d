// Exact PNG decoding for data images (the interior volume's flipbooks): every byte as stored,
// alpha included, with no premultiplication or colour conversion, which a browser's image
// decoding through a canvas does not promise. 8-bit RGB or RGBA, not interlaced (what cutaway
// writes). The page inflates with DecompressionStream, the test tools with node's zlib.

/// {width, height, data} (RGBA, 4 bytes a pixel, row 0 at the top; RGB images get alpha 255)
/// of the PNG `bytes` (a Uint8Array). `inflate(bytes)` returns the zlib stream's contents (a
/// Uint8Array), or a promise of them.
/// @throws Error for a file that is not a PNG of that kind
export async function decodePng(bytes, inflate) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (bytes.length < 8 || view.getUint32(0) !== 0x89504e47) throw new Error('not a PNG');
  let width = 0, height = 0, channels = 0, length = 0;
  const idat = [];
  for (let at = 8; at + 8 <= bytes.length;) {
    const size = view.getUint32(at);
    const type = String.fromCharCode(...bytes.subarray(at + 4, at + 8));
    const body = bytes.subarray(at + 8, at + 8 + size);
    if (type === 'IHDR') {
      width = view.getUint32(at + 8);
      height = view.getUint32(at + 12);
      const [depth, colourType, , , interlace] = body.subarray(8, 13);
      channels = { 2: 3, 6: 4 }[colourType];
      if (depth !== 8 || !channels || interlace) throw new Error('unsupported PNG layout');
    } else if (type === 'IDAT') {
      idat.push(body);
      length += body.length;
    }
    at += 12 + size;
  }
  const compressed = new Uint8Array(length);
  let offset = 0;
  for (const part of idat) {
    compressed.set(part, offset);
    offset += part.length;
  }
  const raw = await inflate(compressed);
  const stride = width * channels, out = new Uint8Array(width * height * 4);
  if (raw.length < height * (stride + 1)) throw new Error('truncated PNG data');
  let previous = new Uint8Array(stride);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)];
    const line = raw.slice(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let i = 0; i < stride; ++i) {
      const a = i >= channels ? line[i - channels] : 0, b = previous[i];
      const c = i >= channels ? previous[i - channels] : 0;
      let add = 0;
      if (filter === 1) add = a;
      else if (filter === 2) add = b;
      else if (filter === 3) add = (a + b) >> 1;
      else if (filter === 4) {
        const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
        add = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      line[i] = (line[i] + add) & 255;
    }
    for (let x = 0; x < width; ++x) {
      for (let k = 0; k < 4; ++k) {
        out[(y * width + x) * 4 + k] = k < channels ? line[x * channels + k] : 255;
      }
    }
    previous = line;
  }
  return { width, height, data: out };
}
