// Records every event a designer fires (by the id of the element it reached the document from) and every
// CSP violation, for the test to read back.
const events = [];
const violations = [];
for (const type of ['load', 'error', 'fieldchange', 'constraintschange', 'progress']) {
  document.addEventListener(type, (e) => {
    if (e.target?.localName === 'tangent-field-designer') events.push({ type, id: e.target.id, detail: e.detail });
  });
}
document.addEventListener('securitypolicyviolation', (e) => violations.push(`${e.violatedDirective}: ${e.blockedURI}`));
window.__record = { events, violations };
