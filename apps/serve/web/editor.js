// editor.js — the chart textarea: errors underlined at their line and column (a layer behind
// the transparent textarea holds the same text with the bad token marked), and the palette line.

const escape = (s) => s.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');

export class ChartEditor {
  constructor(textarea, marks, message) {
    this.textarea = textarea;
    this.marks = marks;
    this.message = message;
    this.error = null;
    textarea.addEventListener('scroll', () => {
      marks.scrollTop = textarea.scrollTop;
      marks.scrollLeft = textarea.scrollLeft;
    });
    textarea.addEventListener('input', () => this.render());
  }

  get text() { return this.textarea.value; }
  set text(value) { this.textarea.value = value; this.render(); }

  // error: {line, column, message, error} (1-based) or null.
  setError(error) {
    this.error = error;
    this.message.textContent = error ? error.error : '';
    this.textarea.setAttribute('aria-invalid', error ? 'true' : 'false');
    this.render();
  }

  render() {
    const lines = this.textarea.value.split('\n');
    const e = this.error;
    const html = lines.map((line, k) => {
      if (!e || e.line !== k + 1) return escape(line);
      // The token at the column (to the next blank), at least one character wide.
      const start = Math.min(Math.max(e.column - 1, 0), line.length);
      let end = start;
      while (end < line.length && !/\s/.test(line[end])) end++;
      const marked = line.slice(start, end) || ' ';
      return escape(line.slice(0, start)) +
        `<span class="error-mark" data-line="${e.line}" data-column="${e.column}">${escape(marked)}</span>` +
        escape(line.slice(end));
    });
    this.marks.innerHTML = html.join('\n') + '\n';
    this.marks.scrollTop = this.textarea.scrollTop;
  }

  // The palette line's colours: {A: '#rrggbb', ...}.
  palette() {
    const colours = {};
    for (const m of this.textarea.value.matchAll(/(^|\s)([A-Za-z])=(#[0-9a-fA-F]{6})(?=\s|$)/gm)) colours[m[2]] = m[3];
    return colours;
  }

  setColour(letter, hex) {
    const re = new RegExp(`(^|\\s)${letter}=#[0-9a-fA-F]{6}(?=\\s|$)`, 'm');
    this.text = this.textarea.value.replace(re, (all, before) => `${before}${letter}=${hex}`);
  }

  // Adds a colour block (every stitch A) and a palette line when the chart has none.
  addColourLayer() {
    if (Object.keys(this.palette()).length) return false;
    const rows = this.textarea.value.split('\n').filter((l) => l.trim() && !l.trim().startsWith('#'));
    const block = rows.map((r) => r.trim().split(/\s+/).map((t) => {
      const cable = /^c(\d)\/(\d)[fb]$/.exec(t);
      return cable ? Array(Number(cable[1]) + Number(cable[2])).fill('A').join(' ') : 'A';
    }).join(' '));
    this.text = this.textarea.value.replace(/\s*$/, '') + '\n\n' + block.join('\n') + '\nA=#c8553d B=#f2e8d5\n';
    return true;
  }
}
