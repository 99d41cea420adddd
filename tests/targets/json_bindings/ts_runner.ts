// Runs the generated TypeScript reader of `remote_driving` (the tests copy this file beside a
// protocol's reader, naming that protocol here, and compile it: json_support.ts_runners) and
// prints one JSON result per input, as the Rust runner does.
//   ts_runner --text FILE      each line of FILE a JSON text, read by `loads`
//   ts_runner VECTORS_JSON     each case: read as its message (`readAs`), as its receiver and
//                              as any message (`parse`), and `loads` of its text agreeing
import { ValidationError, loads, parse, readAs } from "./remote_driving.reader";
import type { Json, MessageName, Receiver } from "./remote_driving.reader";

declare const require: (name: "fs") => { readFileSync(path: string, encoding: "utf-8"): string };
declare const process: { argv: string[] };

interface Case {
  id: string;
  message: MessageName;
  receiver: Receiver;
  json: Json;
}

function verdict(read: () => { readonly name: string }): Record<string, unknown> {
  try {
    return { valid: true, message: read().name };
  } catch (e) {
    if (!(e instanceof ValidationError)) throw e;
    return { valid: false, field: e.field, rule: e.code };
  }
}

function name(read: () => { readonly name: string }): string | null {
  const v = verdict(read);
  return v["valid"] === true ? (v["message"] as string) : null;
}

const fs = require("fs");
const args = process.argv.slice(2);
if (args[0] === "--text" && args[1] !== undefined) {
  const lines = fs.readFileSync(args[1], "utf-8").split("\n").slice(0, -1);
  console.log(JSON.stringify(lines.map((line) => verdict(() => loads(line)))));
} else if (args[0] !== undefined) {
  const doc = JSON.parse(fs.readFileSync(args[0], "utf-8")) as { protocols: { protocol: string; cases: Case[] }[] };
  const cases = doc.protocols.find((p) => p.protocol === "remote_driving")?.cases ?? [];
  const out = cases.map((c) => {
    const own = verdict(() => readAs(c.message, c.json));
    const anyText = verdict(() => loads(JSON.stringify(c.json)));
    const any = verdict(() => parse(c.json));
    return {
      id: c.id,
      ...own,
      as_received: name(() => parse(c.json, c.receiver)),
      as_any: name(() => parse(c.json)),
      text: JSON.stringify(anyText) === JSON.stringify(any),
    };
  });
  console.log(JSON.stringify(out));
}
