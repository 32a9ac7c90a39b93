// The Khronos glTF validator on each file named on the command line (.gltf with its external
// buffers beside it, or .glb). Prints one JSON line per file:
//   {"file": ..., "errors": N, "warnings": N, "messages": ["CODE at POINTER: message", ...]}
// and exits 1 if any file has an error. Install once with `npm ci` in this folder.
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validate(file) {
  const dir = path.dirname(file);
  const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: path.basename(file),
    maxIssues: 50,
    // External buffers are read the way a loader would: the URI, percent-decoded, beside the file.
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.join(dir, decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)));
      }),
  });
  const messages = report.issues.messages
    .filter((m) => m.severity <= 1)
    .map((m) => `${m.code} at ${m.pointer}: ${m.message}`);
  return { file, errors: report.issues.numErrors, warnings: report.issues.numWarnings, messages };
}

(async () => {
  let failed = false;
  for (const file of process.argv.slice(2)) {
    const r = await validate(file);
    failed ||= r.errors > 0;
    console.log(JSON.stringify(r));
  }
  process.exit(failed ? 1 : 0);
})().catch((e) => {
  console.error(e);
  process.exit(2);
});
