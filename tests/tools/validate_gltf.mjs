// Validates glTF files with the Khronos glTF validator (npm gltf-validator).
// Usage: node tests/tools/validate_gltf.mjs FILE.glb|FILE.gltf ...
// Prints one JSON line per file: {"file", "errors", "warnings", "messages" (the errors'),
// "warning_messages" ("CODE POINTER" of each warning, at most 50 issues in all)}; exit code 1
// when any file has an error.
import fs from 'node:fs';
import path from 'node:path';
import validator from 'gltf-validator';

let failed = false;
for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 50,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.join(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)));
      }),
  });
  const errors = report.issues.numErrors;
  const messages = report.issues.messages
    .filter((m) => m.severity === 0)
    .map((m) => `${m.code} ${m.pointer ?? ''}: ${m.message}`);
  const warning_messages = report.issues.messages
    .filter((m) => m.severity === 1)
    .map((m) => `${m.code} ${m.pointer ?? ''}`);
  console.log(JSON.stringify({ file, errors, warnings: report.issues.numWarnings, messages,
                               warning_messages }));
  if (errors > 0) failed = true;
}
process.exit(failed ? 1 : 0);
