// panels.js: the side panel's generated parts: the parameter inputs (from
// the OpenAPI specs, with defaults and one-line help), the legend of
// segments and the list of refinement merges.

import { rgbCss, segmentRgb } from './colours.js';
import { segmentOfNode } from './hierarchy.js';

function element(tag, props = {}, children = []) {
  const e = Object.assign(document.createElement(tag), props);
  e.append(...children);
  return e;
}

function inputFor(spec) {
  if (spec.choices) {
    const select = element('select', {}, spec.choices.map((c) => element('option', { value: c, textContent: c })));
    select.value = spec.default;
    return select;
  }
  if (spec.type === 'boolean') return element('input', { type: 'checkbox', checked: spec.default === 'true' });
  const integer = spec.type === 'integer';
  return element('input', {
    type: 'number', value: spec.default, min: spec.min, max: spec.max, step: integer ? 1 : 0.01,
    inputMode: integer ? 'numeric' : 'decimal',
  });
}

function valueOf(input) {
  return input.type === 'checkbox' ? String(input.checked) : input.value.trim();
}

// Fills `box` with one input per spec.  Returns {values(), reset()}:
// values() gives the parameters that differ from their defaults.
export function buildParamsForm(box, specs) {
  const inputs = specs.map((spec) => {
    const input = inputFor(spec);
    input.id = `param-${spec.name}`;
    input.name = spec.name;
    const range = spec.min !== undefined ? ` (${spec.min} to ${spec.max})` : '';
    box.append(element('div', { className: 'param' }, [
      element('label', { htmlFor: input.id, textContent: spec.name }),
      input,
      element('small', { textContent: `${spec.help}${range}; default ${spec.default}` }),
    ]));
    return { spec, input };
  });
  return {
    values() {
      const out = {};
      for (const { spec, input } of inputs) {
        const v = valueOf(input);
        if (v !== '' && v !== spec.default) out[spec.name] = v;
      }
      return out;
    },
    reset() {
      for (const { spec, input } of inputs) {
        if (input.type === 'checkbox') input.checked = spec.default === 'true';
        else input.value = spec.default;
      }
    },
  };
}

function formatSize(v) {
  return Number(v).toPrecision(3);
}

// A segment's size: "1,234 (12.3%)", or with unit "1,234 points (12.3%)".
export function segmentSize(seg, nPoints, unit = '') {
  return `${seg.size.toLocaleString('en')}${unit} (${((100 * seg.size) / nPoints).toFixed(1)}%)`;
}

// Rows of the legend, each in the Tab order and named as it reads
// ("segment #3: 1,234 points (12.3%)"); onHover(segment id or -1) as the
// mouse enters and leaves a row, and as a row takes and loses the focus.
export function fillLegend(tbody, doc, onHover) {
  tbody.replaceChildren();
  for (const seg of doc.segments) {
    const swatch = element('span', { className: 'swatch' });
    swatch.style.background = rgbCss(segmentRgb(seg.id));
    const row = element('tr', {}, [
      element('td', {}, [swatch]),
      element('td', { textContent: `#${seg.id}` }),
      element('td', { textContent: segmentSize(seg, doc.n_points) }),
      element('td', { textContent: formatSize(seg.feature_size) }),
    ]);
    row.dataset.segment = seg.id;
    row.tabIndex = 0;
    row.setAttribute('aria-label', `segment #${seg.id}: ${segmentSize(seg, doc.n_points, ' points')}`);
    for (const on of ['mouseenter', 'focus']) row.addEventListener(on, () => onHover(seg.id));
    for (const off of ['mouseleave', 'blur']) row.addEventListener(off, () => onHover(-1));
    tbody.append(row);
  }
}

// Marks the legend row of segment id as lit (none for -1); returns it.
export function markLegendRow(tbody, id) {
  for (const row of tbody.querySelectorAll('tr.lit')) row.classList.remove('lit');
  const row = id >= 0 ? tbody.querySelector(`tr[data-segment="${id}"]`) : null;
  if (row) row.classList.add('lit');
  return row;
}

export function fillMerges(list, doc) {
  list.replaceChildren();
  if (!doc.merges.length) list.append(element('li', { className: 'muted', textContent: 'none' }));
  for (const m of doc.merges) {
    const seg = segmentOfNode(doc, m.into);
    list.append(element('li', {
      textContent: `tree node ${m.segment} into node ${m.into}` +
        `${seg >= 0 ? ` (segment #${seg})` : ''}, feature size ${formatSize(m.feature_size)}` +
        `${m.step ? ` (${m.step.replace(/_/g, ' ')})` : ''}`,
    }));
  }
}
