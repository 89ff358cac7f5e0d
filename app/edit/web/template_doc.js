// The template as the page edits it: its YAML text, read with eemeli/yaml (served by the
// editor's server from Debian's node-yaml), and changed by replacing only the text of the
// field that changes. Every other byte stays as it was: comments, layout, the user's number
// formatting. (The library's own stringify would re-lay out the whole file.)
import * as YAML from 'yaml';

/// A YAML scalar written as it is, when it can be: plain words stay plain, anything else is
/// double-quoted (JSON's quoting is valid YAML).
function renderScalar(v) {
  if (typeof v === 'number') return String(v);  // the shortest text that reads back the same
  if (typeof v === 'boolean') return String(v);
  const plain = /^[A-Za-z_][A-Za-z0-9_-]*$/.test(v) &&
                !/^(true|false|null|yes|no|on|off|y|n|~)$/i.test(v);
  return plain ? v : JSON.stringify(v);
}

/// `v` in YAML flow style, compact: [[0, 3], [10, 0.8]], {type: nfold, folds: 5}.
export function renderFlow(v) {
  if (Array.isArray(v)) return `[${v.map(renderFlow).join(', ')}]`;
  if (v !== null && typeof v === 'object') {
    return `{${Object.entries(v).map(([k, x]) => `${renderScalar(k)}: ${renderFlow(x)}`).join(', ')}}`;
  }
  return renderScalar(v);
}

const isObject = (v) => v !== null && typeof v === 'object' && !Array.isArray(v);

/// `v` as the value of a key in block context at `indent` spaces: mappings of more than three
/// keys and lists of mappings as blocks (what a person writes for `surfaces:`), everything
/// else in flow style.
function renderValue(v, indent) {
  const pad = ' '.repeat(indent + 2);
  if (isObject(v) && Object.keys(v).length > 3) {
    return Object.entries(v)
      .map(([k, x]) => `\n${pad}${renderScalar(k)}: ${renderValue(x, indent + 2).trimStart()}`)
      .join('').replace(/: \n/g, ':\n');
  }
  if (Array.isArray(v) && v.length && v.every(isObject)) {
    return v.map((item) => `\n${pad}- ${renderValue(item, indent + 2).trimStart()}`).join('');
  }
  return ` ${renderFlow(v)}`;
}

export class TemplateDoc {
  /// @param text the template's YAML text (may be empty or wrong: `error` says why)
  constructor(text) {
    this.text = text;
    this.doc = YAML.parseDocument(text);
    this.error = this.doc.errors.length ? this.doc.errors[0].message : null;
    this.value = this.error ? null : (this.doc.toJS() ?? {});
  }

  /// The value at `path` (keys and list indices), or undefined.
  get(path) {
    let v = this.value;
    for (const k of path) v = v == null ? undefined : v[k];
    return v;
  }

  /// The YAML node at `path`, or undefined.
  node(path) {
    return path.length ? this.doc.getIn(path, true) : this.doc.contents;
  }

  /// Column (0-based) of the character at offset `at`.
  column(at) {
    return at - (this.text.lastIndexOf('\n', at - 1) + 1);
  }

  /// A new TemplateDoc with `value` at `path`. Only the text of the changed field changes; a
  /// key that is missing is added after its mapping's last key (in a flow mapping, the mapping
  /// is rewritten), a new list item after the list's last one.
  /// @throws Error when the text does not parse or a parent on the path is not a collection
  set(path, value) {
    if (this.error) throw new Error(`the text does not parse: ${this.error}`);
    const node = this.node(path);
    if (node && node.range) {
      // A block collection's range runs on to the next line: keep the line break.
      const start = node.range[0], end = this.trimmedEnd(node.range[1]);
      if (!YAML.isCollection(node) || node.flow) return this.splice(start, end, renderFlow(value));
      const indent = this.column(start);
      if (YAML.isSeq(node) && Array.isArray(value)) {  // stays a block list of flow items
        return this.splice(start, end, value.map((item) => `- ${renderFlow(item)}`)
          .join(`\n${' '.repeat(indent)}`));
      }
      return this.splice(start, end, renderValue(value, indent - 2).trimStart());
    }
    const parentPath = path.slice(0, -1);
    const key = path[path.length - 1];
    const parent = this.node(parentPath);
    if (!parent || !parent.range) {
      const holder = typeof key === 'number' ? [] : {};
      holder[key] = value;
      return this.set(parentPath, holder);
    }
    if (!YAML.isCollection(parent)) throw new Error(`${parentPath.join('.')} is not a collection`);
    const current = this.get(parentPath);
    if (parent.flow || parent.items.length === 0) {
      const changed = Array.isArray(current) ? [...current] : { ...current };
      changed[key] = value;
      return this.splice(parent.range[0], parent.range[1], renderFlow(changed));
    }
    const last = parent.items[parent.items.length - 1];
    const end = this.trimmedEnd((YAML.isPair(last) ? (last.value ?? last.key) : last).range[1]);
    if (YAML.isMap(parent)) {
      const indent = this.column(parent.items[0].key.range[0]);
      return this.splice(end, end, `\n${' '.repeat(indent)}${renderScalar(key)}:${renderValue(value, indent)}`);
    }
    const indent = this.column(parent.items[0].range[0]) - 2;
    return this.splice(end, end, `\n${' '.repeat(indent)}-${renderValue(value, indent).replace(/^\n\s*/, ' ')}`);
  }

  /// A new TemplateDoc without the item or key at `path` (its whole lines in block style).
  remove(path) {
    const parent = this.node(path.slice(0, -1));
    const key = path[path.length - 1];
    if (!parent || !YAML.isCollection(parent)) return this;
    if (parent.flow) {
      const current = this.get(path.slice(0, -1));
      const changed = Array.isArray(current) ? current.filter((_, i) => i !== key) : { ...current };
      if (!Array.isArray(changed)) delete changed[key];
      return this.splice(parent.range[0], parent.range[1], renderFlow(changed));
    }
    const index = YAML.isMap(parent)
      ? parent.items.findIndex((p) => p.key?.value === key) : key;
    const item = parent.items[index];
    if (!item) return this;
    const start = (YAML.isPair(item) ? item.key : item).range[0];
    const end = this.trimmedEnd((YAML.isPair(item) ? (item.value ?? item.key) : item).range[1]);
    const lineStart = this.text.lastIndexOf('\n', start - 1) + 1;
    const lineEnd = this.text.indexOf('\n', end);
    return this.splice(lineStart, lineEnd < 0 ? this.text.length : lineEnd + 1, '');
  }

  /// `at` moved back over white space (and line breaks).
  trimmedEnd(at) {
    while (at > 0 && /\s/.test(this.text[at - 1])) --at;
    return at;
  }

  splice(from, to, replacement) {
    return new TemplateDoc(this.text.slice(0, from) + replacement + this.text.slice(to));
  }
}

/// The text of a new template named `name`: one cylindrical object, no surfaces yet (the
/// first profile drawn becomes the skin).
export function starterText(name) {
  return `format: cutaway-template/1\nname: ${name}\ndescription: ""\nunits: mm\n` +
         `symmetry: {type: cylindrical}\n`;
}
