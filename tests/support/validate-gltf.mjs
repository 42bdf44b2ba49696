// Validates glTF files with the Khronos glTF validator (npm package `gltf-validator`).
// Usage: node validate-gltf.mjs <validator module dir> <file.gltf>...
// Prints one JSON line per file: {"file", "errors", "warnings", "messages": [...]}.
import { createRequire } from "module";
import { readFileSync } from "fs";

const [dir, ...files] = process.argv.slice(2);
const require = createRequire(dir + "/");
const validator = require("gltf-validator");
let failed = false;
for (const file of files) {
  const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), {
    maxIssues: 50,
  });
  const i = report.issues;
  console.log(JSON.stringify({
    file,
    errors: i.numErrors,
    warnings: i.numWarnings,
    messages: i.messages.filter((m) => m.severity <= 1).map((m) => `${m.code}: ${m.message} (${m.pointer ?? ""})`),
  }));
  if (i.numErrors > 0) failed = true;
}
process.exit(failed ? 1 : 0);
