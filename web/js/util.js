// Small DOM helpers.

/// Text made safe to put inside HTML.
export function escapeHtml(text) {
  return String(text).replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' }[c]));
}

/// Appends a <div> with `markup` (already escaped where it holds data) to `parent`.
export function html(parent, markup) {
  const div = document.createElement('div');
  div.innerHTML = markup;
  parent.appendChild(div);
  return div;
}
