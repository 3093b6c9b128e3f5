// Validates glTF files with the Khronos glTF-Validator (npm gltf-validator,
// pinned by web/package-lock.json): prints each file's report summary and
// exits 1 when any file has an error, or when --expect-invalid is given and
// a file has none (the validator is live).
//
// node validate_gltf.mjs NODE_MODULES [--expect-invalid] FILE...
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';

const [modules, ...rest] = process.argv.slice(2);
const expectInvalid = rest[0] === '--expect-invalid';
const files = expectInvalid ? rest.slice(1) : rest;
const validator = createRequire(path.join(modules, 'noop.js'))('gltf-validator');

let failed = false;
for (const file of files) {
  const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), {
    uri: path.basename(file),
    externalResourceFunction: (uri) => Promise.reject(new Error(`external resource ${uri}`)),
  });
  const { numErrors, numWarnings, messages } = report.issues;
  const info = report.info ?? {};
  console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings; ` +
              `${info.totalVertexCount ?? '?'} vertices, ${info.totalTriangleCount ?? '?'} triangles`);
  if (info.hasTextures) console.log(`  textures: ${info.maxUVs ?? '?'} UV sets`);
  for (const m of messages.filter((m) => m.severity <= 1).slice(0, 10)) {
    console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
  }
  if (expectInvalid ? numErrors === 0 : numErrors > 0 || numWarnings > 0) failed = true;
}
process.exit(failed ? 1 : 0);
