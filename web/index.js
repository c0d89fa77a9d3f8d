// Package entry (exports['.']): defines <tangent-field-designer> unless that name is taken, and exports the
// class. For registering under another name, or not at import, use the './element' entry and its define().
import { TAG_NAME, TangentFieldDesigner, define } from './element/element.js';

if (globalThis.customElements && !globalThis.customElements.get(TAG_NAME)) define();

export { TAG_NAME, TangentFieldDesigner, define };
export default TangentFieldDesigner;
