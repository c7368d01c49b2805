// Validates a .glb (or .gltf) file with the Khronos glTF validator (npm `gltf-validator`).
//
//   node scripts/validate-gltf.mjs FILE.glb
//
// The validator package is found in GLTF_VALIDATOR_DIR (a folder whose node_modules holds
// it, as scripts/validate-gltf.sh sets up) or else through NODE_PATH / the usual lookup.
// Prints the issue counts, every error and warning (infos and hints are only counted) and
// exits 1 when there is an error, 2 when the file or the validator cannot be used.

import { readFile } from "node:fs/promises";
import { createRequire } from "node:module";
import path from "node:path";

function loadValidator() {
  const dir = process.env.GLTF_VALIDATOR_DIR;
  const base = dir ? path.join(path.resolve(dir), "package.json") : import.meta.url;
  return createRequire(base)("gltf-validator");
}

const SEVERITY = ["error", "warning", "info", "hint"];

function printIssues(issues) {
  const { numErrors, numWarnings, numInfos, numHints } = issues;
  console.log(
    `${numErrors} error(s), ${numWarnings} warning(s), ${numInfos} info(s), ${numHints} hint(s)` +
      (issues.truncated ? " (truncated)" : ""),
  );
  for (const message of issues.messages) {
    if (message.severity <= 1) {
      const where = message.pointer ?? (message.offset !== undefined ? `byte ${message.offset}` : "");
      console.log(`  ${SEVERITY[message.severity]} ${message.code} ${where}: ${message.message}`);
    }
  }
  const counts = new Map();
  for (const message of issues.messages.filter((m) => m.severity > 1)) {
    const key = `${SEVERITY[message.severity]} ${message.code}`;
    counts.set(key, (counts.get(key) ?? 0) + 1);
  }
  for (const [key, count] of counts) {
    console.log(`  ${key} × ${count}`);
  }
}

async function main() {
  const file = process.argv[2];
  if (!file) {
    console.error("usage: node validate-gltf.mjs FILE.glb");
    return 2;
  }
  let validator;
  try {
    validator = loadValidator();
  } catch (error) {
    console.error(`cannot load gltf-validator (set GLTF_VALIDATOR_DIR or NODE_PATH): ${error.message}`);
    return 2;
  }
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,
    writeTimestamp: false,
  });
  console.log(`${file}: glTF validator ${report.validatorVersion}`);
  if (report.info) {
    const { generator, drawCallCount, totalVertexCount, totalTriangleCount, animationCount } = report.info;
    console.log(
      `  generator ${generator}; ${drawCallCount} draw calls, ${totalVertexCount} vertices, ` +
        `${totalTriangleCount} triangles, ${animationCount} animation(s)`,
    );
  }
  printIssues(report.issues);
  return report.issues.numErrors > 0 ? 1 : 0;
}

main().then(
  (code) => process.exit(code),
  (error) => {
    console.error(`validation failed: ${error}`);
    process.exit(2);
  },
);
