// downloads.js: files the user can save from a result: the labels (one per
// input point, one per line, as `?output=labels`), the JSON document as the
// server sent it, and a binary PLY coloured by segment (with the input's
// faces, as triangles, when it had them).

export function saveBlob(blob, filename) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = filename;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}

export function labelsBlob(labels) {
  return new Blob([labels.join('\n'), '\n'], { type: 'text/plain' });
}

export function jsonBlob(text) {
  return new Blob([text], { type: 'application/json' });
}

// positions: Float32Array #P*3; rgb: Uint8Array #P*3; faces: Uint32Array #F*3 or null.
export function colouredPlyBlob(positions, rgb, faces) {
  const n = positions.length / 3;
  const nf = faces ? faces.length / 3 : 0;
  const header =
    'ply\nformat binary_little_endian 1.0\ncomment pointseg segments\n' +
    `element vertex ${n}\nproperty float x\nproperty float y\nproperty float z\n` +
    'property uchar red\nproperty uchar green\nproperty uchar blue\n' +
    (nf ? `element face ${nf}\nproperty list uchar int vertex_indices\n` : '') +
    'end_header\n';
  const body = new DataView(new ArrayBuffer(15 * n + 13 * nf));
  let at = 0;
  for (let i = 0; i < n; i++, at += 15) {
    for (let c = 0; c < 3; c++) body.setFloat32(at + 4 * c, positions[3 * i + c], true);
    for (let c = 0; c < 3; c++) body.setUint8(at + 12 + c, rgb[3 * i + c]);
  }
  for (let f = 0; f < nf; f++, at += 13) {
    body.setUint8(at, 3);
    for (let c = 0; c < 3; c++) body.setInt32(at + 1 + 4 * c, faces[3 * f + c], true);
  }
  return new Blob([header, body], { type: 'application/ply' });
}

// A binary PLY of points only, to upload the synthetic examples compactly.
export function pointsPlyBlob(positions) {
  const n = positions.length / 3;
  const header = `ply\nformat binary_little_endian 1.0\nelement vertex ${n}\n` +
    'property float x\nproperty float y\nproperty float z\nend_header\n';
  return new Blob([header, positions], { type: 'application/ply' });
}
