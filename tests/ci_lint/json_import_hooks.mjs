// @actions/workflow-parser is built for bundlers: it imports its schema JSON files without the
// `with { type: "json" }` attribute that node requires. These module hooks (registered by
// lint_ci.mjs through module.register) add that attribute to JSON imports that lack it.
// Node 18 calls the context's field importAssertions (node 20 warns when it is read).
export async function load(url, context, nextLoad) {
  const field = "importAttributes" in context ? "importAttributes" : "importAssertions";
  if (url.endsWith(".json") && !context[field]?.type) {
    return nextLoad(url, { ...context, [field]: { type: "json" } });
  }
  return nextLoad(url, context);
}
