// Validates glTF files with the Khronos glTF validator (npm package `gltf-validator`) and exits
// non-zero when any has an error: `node tools/validate_gltf.mjs FILE...`. `.ci/run` runs it on
// `bouncelab export` of every suite scene. Warnings and infos are printed, not failed on.
import { readFile } from "node:fs/promises";
import { createRequire } from "node:module";

const require = createRequire(process.env.GLTF_VALIDATOR_DIR ? `${process.env.GLTF_VALIDATOR_DIR}/` : import.meta.url);
const validator = require("gltf-validator");

let failed = 0;
for (const file of process.argv.slice(2)) {
  const report = await validator.validateBytes(new Uint8Array(await readFile(file)), { uri: file, maxIssues: 100 });
  const { numErrors, numWarnings, numInfos, messages } = report.issues;
  console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos`);
  for (const m of messages.filter((m) => m.severity <= 1)) {
    console.log(`  ${m.severity === 0 ? "error" : "warning"} ${m.code} at ${m.pointer ?? ""}: ${m.message}`);
  }
  if (numErrors > 0) failed += 1;
}
process.exit(failed > 0 ? 1 : 0);
