// Runs the Khronos glTF validator on one GLB or glTF file. Prints one JSON line with the
// issue counts and the error messages; exits 1 when the validator reports an error, 2 when
// the file cannot be read.
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

const file = process.argv[2];
if (!file) {
  console.error('usage: node validate_glb.mjs FILE');
  process.exit(2);
}
let bytes;
try {
  bytes = new Uint8Array(await readFile(file));
} catch (error) {
  console.error(`${file}: ${error.message}`);
  process.exit(2);
}
const report = await validator.validateBytes(bytes, {
  uri: path.basename(file),
  maxIssues: 100,
  externalResourceFunction: (uri) =>
    readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
});
const issues = report.issues;
const errors = issues.messages.filter((m) => m.severity === 0).map((m) => `${m.code} ${m.pointer ?? ''}: ${m.message}`);
console.log(JSON.stringify({
  errors: issues.numErrors,
  warnings: issues.numWarnings,
  infos: issues.numInfos,
  messages: errors,
  warning_codes: [...new Set(issues.messages.filter((m) => m.severity === 1).map((m) => m.code))],
}));
process.exit(issues.numErrors > 0 ? 1 : 0);
