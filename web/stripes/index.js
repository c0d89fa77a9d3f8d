// SPDX-License-Identifier: GPL-2.0-or-later
// Stripe patterns on the page, as one designer composes them: the controller (controller.js), whose calls the
// element makes (docs/js-api.md, "Stripe patterns"), and the "Stripes" panel. The designer hands in the viewer,
// the worker's call and the field the views draw. Imports its own folder.
import { StripesController } from './controller.js';
import { mountStripesPanel } from './panel.js';

// The controller, and given a `panel` container, the Stripes panel. Returns the controller (setStripes(),
// state(), whenIdle(): the element's calls, element/api.js; fieldChanged(), modelChanged(), exportStripes(),
// dispose()).
export function setupStripes({ panel = null, onError = () => {}, ...deps }) {
  const controller = new StripesController({ ...deps, onError });
  if (panel) {
    const view = mountStripesPanel(controller, panel, { onError });
    const notify = controller.onChange;
    controller.onChange = () => {
      notify();
      view.refresh();
    };
  }
  return controller;
}
