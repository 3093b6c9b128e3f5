// Validates Kubernetes manifests against the Kubernetes API's OpenAPI
// schemas (kubernetes-models: one ajv validator per kind, types, required
// fields, enums, formats such as int-or-string and quantities), as
// `kubectl apply --dry-run=client` would before sending them, without a
// cluster. Also checks what a schema cannot: that the Kustomization lists
// every manifest of its folder and that selectors match their pod labels.
//
//   node validate.mjs FILE.yaml...       exit 1 and one line per problem
import { readFileSync, existsSync } from "node:fs";
import { basename, dirname, join } from "node:path";
import { createRequire } from "node:module";
import YAML from "yaml";

const require = createRequire(import.meta.url);
const problems = [];
const objects = [];

function modelFor(apiVersion, kind) {
  // "apps/v1" -> kubernetes-models/apps/v1/Kind; "v1" -> kubernetes-models/v1/Kind
  try {
    return require(`kubernetes-models/${apiVersion}/${kind}`)[kind];
  } catch {
    return null;
  }
}

for (const file of process.argv.slice(2)) {
  const docs = YAML.parseAllDocuments(readFileSync(file, "utf8"));
  for (const doc of docs) {
    if (doc.errors.length) {
      for (const e of doc.errors) problems.push(`${file}: YAML: ${e.message}`);
      continue;
    }
    const obj = doc.toJS();
    if (obj == null) continue;
    const where = `${file}: ${obj.kind ?? "?"} ${obj.metadata?.name ?? obj.metadata?.generateName ?? ""}`;
    if (!obj.apiVersion || !obj.kind) {
      problems.push(`${where}: apiVersion and kind are required`);
      continue;
    }
    if (obj.kind === "Kustomization") {
      for (const r of obj.resources ?? []) {
        if (!existsSync(join(dirname(file), r))) problems.push(`${where}: resource ${r} does not exist`);
      }
      objects.push({ file, obj });
      continue;
    }
    const Model = modelFor(obj.apiVersion, obj.kind);
    if (!Model) {
      problems.push(`${where}: unknown apiVersion/kind ${obj.apiVersion} ${obj.kind}`);
      continue;
    }
    try {
      new Model(obj).validate();
    } catch (e) {
      problems.push(`${where}: ${e.message}`);
    }
    objects.push({ file, obj });
  }
}

// The Kustomization names every manifest beside it (the Job excepted: it
// is created on its own, with generateName).
for (const { file, obj } of objects.filter((o) => o.obj.kind === "Kustomization")) {
  const listed = new Set(obj.resources ?? []);
  for (const o of objects) {
    if (dirname(o.file) !== dirname(file) || o.obj.kind === "Kustomization") continue;
    if (o.obj.kind === "Job") continue;
    if (!listed.has(basename(o.file))) problems.push(`${file}: does not list ${basename(o.file)}`);
  }
}

// Selectors select: Deployment, Service, PodDisruptionBudget.
const podLabels = objects
  .filter((o) => o.obj.kind === "Deployment")
  .map((o) => o.obj.spec?.template?.metadata?.labels ?? {});
function matches(selector) {
  return podLabels.some((labels) =>
    Object.entries(selector ?? {}).every(([k, v]) => labels[k] === v));
}
for (const { file, obj } of objects) {
  if (obj.kind === "Deployment") {
    const sel = obj.spec?.selector?.matchLabels ?? {};
    const labels = obj.spec?.template?.metadata?.labels ?? {};
    if (!Object.entries(sel).every(([k, v]) => labels[k] === v)) {
      problems.push(`${file}: Deployment selector does not match its pod labels`);
    }
  }
  if (obj.kind === "Service" && !matches(obj.spec?.selector)) {
    problems.push(`${file}: Service selector matches no Deployment's pods`);
  }
  if (obj.kind === "PodDisruptionBudget" && !matches(obj.spec?.selector?.matchLabels)) {
    problems.push(`${file}: PodDisruptionBudget selector matches no Deployment's pods`);
  }
}

for (const p of problems) console.error(p);
const n = objects.length;
if (problems.length) {
  console.error(`${problems.length} problem(s) in ${n} object(s)`);
  process.exit(1);
}
console.log(`${n} object(s) valid`);
