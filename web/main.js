// The app page (index.html): one <tangent-field-designer controls="full"> filling the window, with the
// page-wide keyboard shortcuts, the ?bench=1 benchmark, and window.tvf as an alias of the element for the
// documented API (docs/js-api.md) — on this page only; embedding pages use their elements.
import { APP_PAGE, define } from './element/element.js';

const element = document.querySelector('tangent-field-designer');
define();
element[APP_PAGE]();
window.tvf = element;
