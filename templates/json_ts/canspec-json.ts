/**
 * The strict JSON text reader and the checks every message applies, the same in every generated
 * protocol (each `<protocol>.reader.ts` gives the tables). Check order, as in every binding: the
 * value is an object; every key is present (in document order); no other key (the least in
 * code-point order); a command's `cmd`; then per field its JSON type, its declared type's range
 * (or a string's length), and its documented values (enum, or range and sentinels).
 * Plain TypeScript, no dependencies.
 */

/** A decoded JSON value. */
export type Json = null | boolean | number | string | Json[] | JsonObject;
export interface JsonObject {
  [key: string]: Json;
}

export type ErrorCode =
  | "object"
  | "required"
  | "unexpected"
  | "type"
  | "type_range"
  | "enum"
  | "range"
  | "length"
  | "cmd"
  | "json"
  | "duplicate";

/**
 * A JSON value that breaks the protocol. `messageName`: the message it was read as ("message"
 * while no message is told apart); `field`: the JSON key at fault ("" when the value is not a
 * JSON object); `value`: the offending value; `code`: what was broken; `rule`: the rule in words.
 */
export class ValidationError extends Error {
  constructor(
    readonly messageName: string,
    readonly field: string,
    readonly value: unknown,
    readonly code: ErrorCode,
    readonly rule: string,
  ) {
    super(`${field ? `${messageName}.${field}` : messageName}: ${show(value)} ${rule}`);
    this.name = "ValidationError";
  }
}

function show(value: unknown): string {
  let text: string;
  try {
    text = typeof value === "number" && !Number.isFinite(value) ? String(value) : (JSON.stringify(value) ?? String(value));
  } catch {
    text = String(value);
  }
  return text.length > 80 ? `${text.slice(0, 77)}...` : text;
}

/** A field's rules (generated per message). */
export interface Field {
  readonly key: string;
  readonly kind: "integer" | "number" | "boolean" | "string";
  readonly typeLo?: number;
  readonly typeHi?: number;
  readonly typeRule: string;
  readonly typeRangeRule?: string;
  readonly minLength?: number;
  readonly maxLength?: number;
  readonly lengthRule?: string;
  readonly values?: readonly (number | string)[];
  readonly lo?: number;
  readonly hi?: number;
  readonly sentinels?: readonly number[];
  readonly valueRule?: string;
}

/** A message's rules: its keys in document order, its command number and fields. */
export interface MessageRules {
  readonly name: string;
  readonly keys: readonly string[];
  readonly cmd?: { readonly field: Field; readonly value: number };
  readonly fields: readonly Field[];
}

/** How a plan selects a message: any marker key present, or valid as it (tried), or the default. */
export interface Branch {
  readonly message: string;
  readonly markers: readonly string[];
  readonly tried: boolean;
}

/** How a receiver (or anyone) tells the messages apart (ir/json_fields.py). */
export interface Plan {
  readonly commands: readonly (readonly [number, readonly Branch[]])[];
  readonly commandRule: string;
  readonly plain: readonly Branch[];
}

const hasOwn = (obj: object, key: string): boolean => Object.prototype.hasOwnProperty.call(obj, key);

function isObject(value: unknown): value is JsonObject {
  return typeof value === "object" && value !== null && !Array.isArray(value);
}

/** Code-point order (JavaScript's `<` compares UTF-16 code units). */
function codePointCompare(a: string, b: string): number {
  const x = Array.from(a, (c) => c.codePointAt(0) ?? 0);
  const y = Array.from(b, (c) => c.codePointAt(0) ?? 0);
  for (let i = 0; i < Math.min(x.length, y.length); i++) {
    const d = (x[i] ?? 0) - (y[i] ?? 0);
    if (d !== 0) {
      return d;
    }
  }
  return x.length - y.length;
}

/** The field's JSON type and its declared type's range (or a string's length). */
function checkType(message: string, f: Field, value: Json): void {
  const fail = (code: ErrorCode, rule: string): never => {
    throw new ValidationError(message, f.key, value, code, rule);
  };
  if (f.kind === "boolean") {
    if (typeof value !== "boolean") fail("type", f.typeRule);
  } else if (f.kind === "string") {
    if (typeof value !== "string") return fail("type", f.typeRule);
    const length = Array.from(value).length; // in code points
    if ((f.minLength !== undefined && length < f.minLength) || (f.maxLength !== undefined && length > f.maxLength)) {
      fail("length", f.lengthRule ?? "");
    }
  } else {
    if (typeof value !== "number" || !Number.isFinite(value)) return fail("type", f.typeRule);
    if (f.kind === "integer" && !Number.isInteger(value)) fail("type", f.typeRule);
    if ((f.typeLo !== undefined && value < f.typeLo) || (f.typeHi !== undefined && value > f.typeHi)) {
      fail("type_range", f.typeRangeRule ?? "");
    }
  }
}

/** The field's documented values: its enum, or its range and sentinels. */
function checkValue(message: string, f: Field, value: Json): void {
  if (f.values !== undefined) {
    if (!f.values.includes(value as number | string)) {
      throw new ValidationError(message, f.key, value, "enum", f.valueRule ?? "");
    }
  } else if (typeof value === "number" && (f.lo !== undefined || f.hi !== undefined)) {
    const inside = (f.lo === undefined || f.lo <= value) && (f.hi === undefined || value <= f.hi);
    if (!inside && !(f.sentinels ?? []).includes(value)) {
      throw new ValidationError(message, f.key, value, "range", f.valueRule ?? "");
    }
  }
}

/** `value` read as message `m`: returned unchanged when valid, else ValidationError. */
export function checkMessage(m: MessageRules, value: Json): JsonObject {
  if (!isObject(value)) {
    throw new ValidationError(m.name, "", value, "object", "must be a JSON object");
  }
  for (const key of m.keys) {
    if (!hasOwn(value, key)) throw new ValidationError(m.name, key, null, "required", "is required");
  }
  const unknown = Object.keys(value).filter((k) => !m.keys.includes(k));
  if (unknown.length > 0) {
    const key = unknown.reduce((a, b) => (codePointCompare(a, b) <= 0 ? a : b));
    throw new ValidationError(m.name, key, value[key], "unexpected", `is not a field of ${m.name}`);
  }
  if (m.cmd !== undefined) {
    const cmd = value[m.cmd.field.key] ?? null;
    checkType(m.name, m.cmd.field, cmd);
    if (cmd !== m.cmd.value) throw new ValidationError(m.name, m.cmd.field.key, cmd, "cmd", m.cmd.field.valueRule ?? "");
  }
  for (const f of m.fields) {
    const v = value[f.key] ?? null;
    checkType(m.name, f, v);
    checkValue(m.name, f, v);
  }
  return value;
}

function commandNumber(value: Json | undefined): number | undefined {
  return typeof value === "number" && Number.isInteger(value) ? value : undefined;
}

function pick(messages: ReadonlyMap<string, MessageRules>, group: readonly Branch[], obj: JsonObject): string {
  for (const b of group) {
    const m = messages.get(b.message);
    if (m === undefined) continue;
    if (b.tried) {
      try {
        checkMessage(m, obj);
        return b.message;
      } catch (e) {
        if (!(e instanceof ValidationError)) throw e;
        continue;
      }
    }
    if (b.markers.length === 0 || b.markers.some((k) => hasOwn(obj, k))) {
      checkMessage(m, obj);
      return b.message;
    }
  }
  throw new ValidationError("message", "cmd", null, "required", "is required"); // no group is empty: never reached
}

/** The name of the message `value` is under `plan`, once checked as it; else ValidationError. */
export function select(messages: ReadonlyMap<string, MessageRules>, plan: Plan, value: Json): string {
  if (!isObject(value)) {
    throw new ValidationError("message", "", value, "object", "must be a JSON object");
  }
  if (plan.commands.length > 0 && hasOwn(value, "cmd")) {
    const n = commandNumber(value["cmd"]);
    const group = plan.commands.find(([c]) => c === n);
    if (group === undefined) throw new ValidationError("message", "cmd", value["cmd"], "cmd", plan.commandRule);
    return pick(messages, group[1], value);
  }
  if (plan.plain.length === 0) {
    throw new ValidationError("message", "cmd", null, "required", "is required");
  }
  return pick(messages, plan.plain, value);
}

/** NaN or Infinity in the text, or a fraction or exponent beyond every double (1e400). */
class NotFinite {
  constructor(readonly value: number) {}
}

type Parsed = Json | NotFinite;

const NUMBER = /-?(?:0|[1-9][0-9]*)(\.[0-9]+)?([eE][-+]?[0-9]+)?/y;
const WORDS: readonly (readonly [string, Parsed])[] = [
  ["true", true],
  ["false", false],
  ["null", null],
  ["NaN", new NotFinite(NaN)],
  ["Infinity", new NotFinite(Infinity)],
  ["-Infinity", new NotFinite(-Infinity)],
];
const ESCAPES: Readonly<Record<string, string>> = { '"': '"', "\\": "\\", "/": "/", b: "\b", f: "\f", n: "\n", r: "\r", t: "\t" };

/**
 * Reads JSON text strictly: as Python's `json.loads` reads it (NaN and Infinity are read, then
 * refused), with each object checked when it closes, its members in order: a number that is not
 * finite is refused (code `json`, naming its key), so is a key given twice (`duplicate`).
 */
class Reader {
  private at = 0;

  constructor(private readonly text: string) {}

  read(): Json {
    const value = this.value();
    this.space();
    if (this.at !== this.text.length) this.fail("extra data");
    if (value instanceof NotFinite) {
      throw new ValidationError("message", "", value.value, "json", "is not JSON (numbers are finite)");
    }
    return value;
  }

  private fail(what: string): never {
    throw new ValidationError("message", "", this.text, "json", `is not JSON text (${what} at ${this.at})`);
  }

  private space(): void {
    while (" \t\n\r".includes(this.text.charAt(this.at)) && this.at < this.text.length) this.at++;
  }

  private value(): Parsed {
    this.space();
    const c = this.text.charAt(this.at);
    if (c === "{") return this.object();
    if (c === "[") return this.array();
    if (c === '"') return this.string();
    for (const [word, value] of WORDS) {
      if (this.text.startsWith(word, this.at)) {
        this.at += word.length;
        return value;
      }
    }
    NUMBER.lastIndex = this.at;
    const m = NUMBER.exec(this.text);
    if (m === null) this.fail("expecting a value");
    this.at += m[0].length;
    const n = Number(m[0]);
    if (Number.isFinite(n)) return n;
    // A fraction or exponent beyond every double is refused; an integer literal is a finite
    // number (Python reads it as an int): beyond every double, it reads as the largest one of
    // its sign, outside every declared type's range as the exact integer is.
    return m[1] !== undefined || m[2] !== undefined ? new NotFinite(n) : Math.sign(n) * Number.MAX_VALUE;
  }

  private expect(c: string): void {
    this.space();
    if (this.text.charAt(this.at) !== c) this.fail(`expecting '${c}'`);
    this.at++;
  }

  private array(): Json[] {
    this.at++;
    const out: Json[] = [];
    this.space();
    if (this.text.charAt(this.at) === "]") {
      this.at++;
      return out;
    }
    for (;;) {
      const v = this.value();
      out.push(v instanceof NotFinite ? v.value : v);
      this.space();
      if (this.text.charAt(this.at) === "]") {
        this.at++;
        return out;
      }
      this.expect(",");
    }
  }

  private object(): JsonObject {
    this.at++;
    const members: [string, Parsed][] = [];
    this.space();
    if (this.text.charAt(this.at) === "}") {
      this.at++;
    } else {
      for (;;) {
        this.space();
        if (this.text.charAt(this.at) !== '"') this.fail("expecting a key");
        const key = this.string();
        this.expect(":");
        members.push([key, this.value()]);
        this.space();
        if (this.text.charAt(this.at) === "}") {
          this.at++;
          break;
        }
        this.expect(",");
      }
    }
    const obj: JsonObject = Object.create(null) as JsonObject;
    for (const [key, value] of members) {
      if (value instanceof NotFinite) {
        throw new ValidationError("message", key, value.value, "json", "is not JSON (numbers are finite)");
      }
      if (hasOwn(obj, key)) throw new ValidationError("message", key, value, "duplicate", "appears twice in one object");
      obj[key] = value;
    }
    return obj;
  }

  private string(): string {
    this.at++;
    let out = "";
    for (;;) {
      const c = this.text.charAt(this.at);
      if (this.at >= this.text.length) this.fail("unterminated string");
      this.at++;
      if (c === '"') return out;
      if (c < " ") this.fail("control character in a string");
      if (c !== "\\") {
        out += c;
        continue;
      }
      const e = this.text.charAt(this.at++);
      if (e === "u") {
        const hex = this.text.slice(this.at, this.at + 4);
        if (!/^[0-9a-fA-F]{4}$/.test(hex)) this.fail("invalid \\u escape");
        out += String.fromCharCode(parseInt(hex, 16));
        this.at += 4;
      } else {
        const plain = ESCAPES[e];
        if (plain === undefined) this.fail("invalid escape");
        out += plain;
      }
    }
  }
}

/** JSON text as a value, refusing what JSON does not allow (see Reader); else ValidationError. */
export function readText(text: string): Json {
  return new Reader(text).read();
}
