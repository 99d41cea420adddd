// Validates every case of the JSON-protocol vectors with ajv (draft 2020-12, every strict option
// on — strictSchema, strictNumbers, strictTypes, strictTuples, strictRequired: no keyword declared
// for the schemas, which carry canspec's annotations in $comment; every required key declared):
// against the case's own message schema, its receiver's schema and the whole-protocol schema.
// Usage: NODE_PATH=<node_modules> node ajv_check.cjs SCHEMA_DIR VECTORS_JSON [SCHEMA_DIR VECTORS_JSON ...]
// Prints one JSON array: [{input, protocol, id, own, own_fields, received, any}] (fields named by
// the errors; `input`: the index of the SCHEMA_DIR VECTORS_JSON pair, each checked by an ajv of its own).
"use strict";
const fs = require("fs");
const path = require("path");
const Ajv2020 = require("ajv/dist/2020").default;

function faultFields(errors) {
  const fields = new Set();
  for (const e of errors || []) {
    if (e.keyword === "required") fields.add(e.params.missingProperty);
    else if (e.keyword === "additionalProperties") fields.add(e.params.additionalProperty);
    else fields.add(e.instancePath.split("/")[1] === undefined ? "" : e.instancePath.split("/")[1].replace(/~1/g, "/").replace(/~0/g, "~"));
  }
  return [...fields].sort();
}

function check(input, schemaRoot, vectorsPath, results) {
  const ajv = new Ajv2020({ strict: true, allErrors: true });
  const vectors = JSON.parse(fs.readFileSync(vectorsPath, "utf8"));
  for (const proto of vectors.protocols) {
    const dir = path.join(schemaRoot, proto.protocol);
    const validators = {};
    const get = (name) => {
      if (!validators[name]) {
        const schema = JSON.parse(fs.readFileSync(path.join(dir, `${name}.schema.json`), "utf8"));
        validators[name] = ajv.compile(schema);
      }
      return validators[name];
    };
    for (const c of proto.cases) {
      const own = get(c.message);
      const ok = own(c.json);
      results.push({
        input,
        protocol: proto.protocol,
        id: c.id,
        own: ok,
        own_fields: faultFields(own.errors),
        received: get(`to_${c.receiver}`)(c.json),
        any: get("protocol")(c.json),
      });
    }
  }
}

const args = process.argv.slice(2);
if (args.length === 0 || args.length % 2 !== 0) {
  console.error("usage: node ajv_check.cjs SCHEMA_DIR VECTORS_JSON [SCHEMA_DIR VECTORS_JSON ...]");
  process.exit(2);
}
const results = [];
for (let i = 0; i < args.length; i += 2) {
  check(i / 2, args[i], args[i + 1], results);
}
process.stdout.write(JSON.stringify(results) + "\n");
