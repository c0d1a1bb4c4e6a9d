// read_file.js: reads a chosen point file in parse_worker.js (a module
// worker), so the page's main thread stays free for drawing and input
// while a big scan is read, un-gzipped and parsed.
//   const reading = readPointFile(file, (phase) => ...);
//   reading.promise  resolves {gzip, count, positions, faces} (formats.js'
//                    result, and whether the file was gzip); rejects with
//                    the parser's message (FormatError text) as an Error
//   reading.cancel() stops the worker; the promise rejects with ReadCancelled

export class ReadCancelled extends Error {}

export function readPointFile(file, onPhase = () => {}) {
  const worker = new Worker(new URL('./parse_worker.js', import.meta.url), { type: 'module' });
  let cancel;
  const promise = new Promise((ok, fail) => {
    const end = (settle, value) => {
      worker.terminate();
      settle(value);
    };
    cancel = () => end(fail, new ReadCancelled(`reading ${file.name} was cancelled`));
    worker.onmessage = ({ data }) => {
      if (data.phase) onPhase(data.phase);
      else if (data.parsed) end(ok, data.parsed);
      else end(fail, new Error(data.error));
    };
    // The worker's script did not load or threw outside onmessage.
    worker.onerror = (e) => {
      e.preventDefault();
      end(fail, new Error(`the file reader stopped: ${e.message || 'parse_worker.js did not load'}`));
    };
  });
  worker.postMessage(file);
  return { promise, cancel };
}
