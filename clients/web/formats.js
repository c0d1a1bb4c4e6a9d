// formats.js: reads the uploaded file in the browser, so the viewer has
// the coordinates (the server's JSON carries labels, not points); the page
// runs it in parse_worker.js, off its main thread.  Recognizes the
// formats the daemon does, from the content: PLY (ascii, binary little and
// big endian, any vertex properties, faces), OFF, OBJ, XYZ/CSV and the
// JSON request document.  Returns {count, positions: Float32Array #P*3,
// faces: Uint32Array #F*3 (triangles, fans of polygons) or null}.  Points
// of dimension 2 get z = 0; of dimension > 3 keep their first three.
// A gzip-compressed file is undone first by gunzip (the browser's own
// DecompressionStream), as the daemon undoes Content-Encoding: gzip.

const PLY_TYPES = {
  char: ['getInt8', 1], int8: ['getInt8', 1], uchar: ['getUint8', 1], uint8: ['getUint8', 1],
  short: ['getInt16', 2], int16: ['getInt16', 2], ushort: ['getUint16', 2], uint16: ['getUint16', 2],
  int: ['getInt32', 4], int32: ['getInt32', 4], uint: ['getUint32', 4], uint32: ['getUint32', 4],
  float: ['getFloat32', 4], float32: ['getFloat32', 4], double: ['getFloat64', 8], float64: ['getFloat64', 8],
};

export class FormatError extends Error {}

function plyType(name) {
  const t = PLY_TYPES[name];
  if (!t) throw new FormatError(`PLY: unknown property type '${name}'`);
  return t;
}

function parsePlyHeader(bytes) {
  const head = new TextDecoder('latin1').decode(bytes.subarray(0, Math.min(bytes.length, 65536)));
  const end = head.search(/end_header\r?\n/);
  if (end < 0) throw new FormatError('PLY: no end_header line');
  const bodyStart = end + head.slice(end).indexOf('\n') + 1;
  const elements = [];
  let format = null;
  for (const line of head.slice(0, end).split(/\r?\n/)) {
    const w = line.trim().split(/\s+/);
    if (w[0] === 'format') format = w[1];
    else if (w[0] === 'element') elements.push({ name: w[1], count: Number(w[2]), props: [] });
    else if (w[0] === 'property' && elements.length) {
      const props = elements[elements.length - 1].props;
      if (w[1] === 'list') props.push({ name: w[4], list: true, countType: plyType(w[2]), type: plyType(w[3]) });
      else props.push({ name: w[2], list: false, type: plyType(w[1]) });
    }
  }
  if (!['ascii', 'binary_little_endian', 'binary_big_endian'].includes(format))
    throw new FormatError(`PLY: unsupported format '${format}'`);
  return { format, elements, bodyStart };
}

// Reads PLY values one at a time, from binary (DataView) or ascii tokens.
function plyReader(bytes, header) {
  if (header.format === 'ascii') {
    const text = new TextDecoder('latin1').decode(bytes.subarray(header.bodyStart));
    const re = /\S+/g;
    return () => {
      const m = re.exec(text);
      if (!m) throw new FormatError('PLY: the body ends early');
      return Number(m[0]);
    };
  }
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const little = header.format === 'binary_little_endian';
  let at = header.bodyStart;
  return ([getter, size]) => {
    if (at + size > view.byteLength) throw new FormatError('PLY: the body ends early');
    const v = view[getter](at, little);
    at += size;
    return v;
  };
}

function readPlyVertices(el, read, positions) {
  const slot = el.props.map((p) => ['x', 'y', 'z'].indexOf(p.name));
  if (!slot.includes(0) || !slot.includes(1)) throw new FormatError('PLY: vertex has no x and y');
  for (let i = 0; i < el.count; i++) {
    for (let j = 0; j < el.props.length; j++) {
      const p = el.props[j];
      if (p.list) {
        const n = read(p.countType);
        for (let k = 0; k < n; k++) read(p.type);
      } else {
        const v = read(p.type);
        if (slot[j] >= 0) positions[3 * i + slot[j]] = v;
      }
    }
  }
}

function readPlyFaces(el, read, faces) {
  for (let i = 0; i < el.count; i++) {
    for (const p of el.props) {
      if (!p.list) {
        read(p.type);
        continue;
      }
      const n = read(p.countType);
      const ring = [];
      for (let k = 0; k < n; k++) ring.push(read(p.type));
      if (p.name === 'vertex_indices' || p.name === 'vertex_index') addPolygon(faces, ring);
    }
  }
}

function skipPlyElement(el, read) {
  for (let i = 0; i < el.count; i++)
    for (const p of el.props) {
      const n = p.list ? read(p.countType) : 1;
      for (let k = 0; k < n; k++) read(p.type);
    }
}

function parsePly(bytes) {
  const header = parsePlyHeader(bytes);
  const read = plyReader(bytes, header);
  let positions = null;
  const faces = [];
  for (const el of header.elements) {
    if (el.name === 'vertex') {
      positions = new Float32Array(3 * el.count);
      readPlyVertices(el, read, positions);
    } else if (el.name === 'face') readPlyFaces(el, read, faces);
    else skipPlyElement(el, read);
  }
  if (!positions) throw new FormatError('PLY: no vertex element');
  return finish(positions, faces);
}

// Appends a polygon (vertex indices) as a triangle fan.
function addPolygon(faces, ring) {
  for (let k = 1; k + 1 < ring.length; k++) faces.push(ring[0], ring[k], ring[k + 1]);
}

function finish(positions, faces) {
  const count = positions.length / 3;
  for (const v of faces)
    if (!(v >= 0 && v < count)) throw new FormatError(`face index ${v} is outside 0..${count - 1}`);
  return { count, positions, faces: faces.length ? Uint32Array.from(faces) : null };
}

function dataLines(text) {
  return text.split(/\r?\n/).map((l) => l.replace(/#.*/, '').trim()).filter((l) => l.length);
}

function parseOff(text) {
  const lines = dataLines(text);
  const first = lines[0].replace(/^[STCN4n]*OFF/, '').trim();
  const counts = (first.length ? first : lines[1]).split(/\s+/).map(Number);
  let at = first.length ? 1 : 2;
  const [nv, nf] = counts;
  if (!(nv >= 0 && nf >= 0) || at + nv > lines.length) throw new FormatError('OFF: bad vertex or face count');
  const positions = new Float32Array(3 * nv);
  for (let i = 0; i < nv; i++, at++) setPoint(positions, i, lines[at].split(/\s+/));
  const faces = [];
  for (let i = 0; i < nf && at < lines.length; i++, at++) {
    const w = lines[at].split(/\s+/).map(Number);
    addPolygon(faces, w.slice(1, 1 + w[0]));
  }
  return finish(positions, faces);
}

function parseObj(text) {
  const coords = [];
  const faces = [];
  for (const line of text.split(/\r?\n/)) {
    const w = line.trim().split(/\s+/);
    if (w[0] === 'v') coords.push(Number(w[1]), Number(w[2]), w.length > 3 ? Number(w[3]) : 0);
    else if (w[0] === 'f') {
      const base = coords.length / 3;
      const ring = w.slice(1).map((s) => {
        const i = parseInt(s, 10);
        return i < 0 ? base + i : i - 1;
      });
      addPolygon(faces, ring);
    }
  }
  return finish(Float32Array.from(coords), faces);
}

// Writes the first three of the numeric words (z = 0 for 2 columns).
function setPoint(positions, i, words) {
  for (let c = 0; c < 3; c++) positions[3 * i + c] = c < words.length ? Number(words[c]) : 0;
}

function parseXyz(text) {
  const lines = dataLines(text);
  if (lines.length && !/^[-+.\d]/.test(lines[0])) lines.shift();
  const positions = new Float32Array(3 * lines.length);
  lines.forEach((l, i) => setPoint(positions, i, l.split(/[\s,;]+/)));
  if (lines.length && positions.some((v) => Number.isNaN(v))) throw new FormatError('XYZ: a value is not a number');
  return finish(positions, []);
}

function parseJson(text) {
  const doc = JSON.parse(text);
  const pts = doc.points;
  if (!Array.isArray(pts)) throw new FormatError('JSON: no "points" array');
  if (pts.length && Array.isArray(pts[0])) {
    const positions = new Float32Array(3 * pts.length);
    pts.forEach((p, i) => setPoint(positions, i, p));
    return finish(positions, []);
  }
  const dim = doc.dimension || 3;
  const n = Math.floor(pts.length / dim);
  const positions = new Float32Array(3 * n);
  for (let i = 0; i < n; i++) setPoint(positions, i, pts.slice(dim * i, dim * i + Math.min(dim, 3)));
  return finish(positions, []);
}

// True when bytes start with the gzip magic 1f 8b.
export function isGzip(bytes) {
  return bytes.length >= 2 && bytes[0] === 0x1f && bytes[1] === 0x8b;
}

// bytes: Uint8Array of a gzip file.  Resolves to the decompressed
// Uint8Array; rejects with a FormatError saying why it could not.
export async function gunzip(bytes) {
  if (typeof DecompressionStream !== 'function')
    throw new FormatError('gzip: this browser cannot decompress (no DecompressionStream); upload the file uncompressed');
  try {
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('gzip'));
    return new Uint8Array(await new Response(stream).arrayBuffer());
  } catch (err) {
    throw new FormatError(`gzip: the file starts like gzip but does not decompress (${err.message || err})`);
  }
}

// bytes: Uint8Array of the whole file, already decompressed (see gunzip).
// A UTF-8 byte order mark in front is skipped, as the daemon does.
export function parsePointFile(bytes) {
  if (isGzip(bytes)) throw new FormatError('the file is still gzip-compressed: gunzip it first');
  if (bytes[0] === 0xef && bytes[1] === 0xbb && bytes[2] === 0xbf) bytes = bytes.subarray(3);
  const start = new TextDecoder('latin1').decode(bytes.subarray(0, 64)).trimStart();
  if (start.startsWith('ply')) return parsePly(bytes);
  const text = new TextDecoder().decode(bytes);
  const firstData = text.slice(0, 4096).split(/\r?\n/).map((l) => l.replace(/#.*/, '').trim()).find((l) => l);
  if (firstData && /^[STCN4n]*OFF$/.test(firstData.split(/\s+/)[0])) return parseOff(text);
  if (start.startsWith('{')) return parseJson(text);
  if (/^\s*v\s/m.test(text.slice(0, 65536))) return parseObj(text);
  return parseXyz(text);
}
