// Checks CI files without the network (docs/dev/testing.md, "Sanitizers and CI"):
//   node lint_ci.mjs github FILE...   GitHub Actions workflows, with GitHub's own parser
//                                      (@actions/workflow-parser: the workflow schema, expressions,
//                                      job graph), as the Actions service reads them
//   node lint_ci.mjs gitlab FILE...   GitLab CI files, against GitLab's CI JSON schema (the copy
//                                      gitlab-ci-local ships and validates with), with ajv
// Prints "FILE:LINE:COLUMN: message" for every problem; exit 0 when every file is valid, 1 when one
// is not, 2 on a wrong command line.
import { readFileSync } from "node:fs";
import { register } from "node:module";
import Ajv from "ajv";
import { schema as gitlabSchema } from "gitlab-ci-local/src/schema/schema.js";
import { LineCounter, parseDocument } from "yaml";

// Loaded after the hooks that let it import its JSON schema (json_import_hooks.mjs).
register("./json_import_hooks.mjs", import.meta.url);
const { convertWorkflowTemplate, NoOperationTraceWriter, parseWorkflow } = await import("@actions/workflow-parser");

async function githubProblems(file, content) {
  const parsed = parseWorkflow({ name: file, content }, new NoOperationTraceWriter());
  // The conversion checks what the schema cannot (jobs' needs, expressions, ...) and adds its errors
  // to the same context.
  if (parsed.value) await convertWorkflowTemplate(parsed.context, parsed.value);
  return parsed.context.errors.getErrors().map((e) => ({
    line: e.range?.start.line ?? 1,
    column: e.range?.start.column ?? 1,
    message: e.rawMessage,
  }));
}

// The options gitlab-ci-local validates with: the schema's own keywords and union types allowed,
// formats (URIs of documentation links) not checked.
const validateGitlab = new Ajv({
  allErrors: true,
  allowUnionTypes: true,
  validateFormats: false,
  strictTypes: false,
  keywords: ["markdownDescription"],
}).compile(gitlabSchema);

function gitlabProblems(file, content) {
  const lineCounter = new LineCounter();
  const document = parseDocument(content, { lineCounter });
  const at = (offset) => lineCounter.linePos(offset ?? 0);
  if (document.errors.length > 0) {
    return document.errors.map((e) => ({ ...at(e.pos[0]), column: at(e.pos[0]).col, message: e.message }));
  }
  if (validateGitlab(document.toJS())) return [];
  return validateGitlab.errors.map((e) => {
    // The YAML node the error is about (its instance path), for its line.
    const path = e.instancePath.split("/").slice(1).map((p) => p.replaceAll("~1", "/").replaceAll("~0", "~"));
    const node = document.getIn(path, true);
    const where = at(node?.range?.[0]);
    const extra = e.params?.additionalProperty ? ` '${e.params.additionalProperty}'` : "";
    return { line: where.line, column: where.col, message: `${e.instancePath || "/"} ${e.message}${extra}` };
  });
}

const [kind, ...files] = process.argv.slice(2);
const checkers = { github: githubProblems, gitlab: gitlabProblems };
if (!checkers[kind] || files.length === 0) {
  console.error("usage: node lint_ci.mjs github|gitlab FILE...");
  process.exit(2);
}
let failed = false;
for (const file of files) {
  const problems = await checkers[kind](file, readFileSync(file, "utf8"));
  for (const p of problems) console.log(`${file}:${p.line}:${p.column}: ${p.message}`);
  if (problems.length > 0) failed = true;
  else console.log(`${file}: valid ${kind} CI file`);
}
process.exit(failed ? 1 : 0);
