// parse_worker.js: a module worker that reads a chosen file off the
// page's main thread, so a scan of hundreds of MB does not freeze the page.
// Gets the File (a Blob: passed by reference, not copied), reads it,
// undoes gzip (formats.js gunzip) and parses it (parsePointFile).  Posts
// {phase: 'reading' | 'decompressing' | 'parsing'} as it goes, then
// {parsed: {gzip, count, positions, faces}} with the typed arrays
// transferred, or {error: message} (a FormatError's message as it is).
// Started by read_file.js, one worker per file.

import { gunzip, isGzip, parsePointFile } from './formats.js';

self.onmessage = async ({ data: file }) => {
  try {
    self.postMessage({ phase: 'reading' });
    let bytes = new Uint8Array(await file.arrayBuffer());
    const gzip = isGzip(bytes);
    if (gzip) {
      self.postMessage({ phase: 'decompressing' });
      bytes = await gunzip(bytes);
    }
    self.postMessage({ phase: 'parsing' });
    const { count, positions, faces } = parsePointFile(bytes);
    bytes = null;
    const transfer = faces ? [positions.buffer, faces.buffer] : [positions.buffer];
    self.postMessage({ parsed: { gzip, count, positions, faces } }, transfer);
  } catch (err) {
    self.postMessage({ error: String((err && err.message) || err) });
  }
};
