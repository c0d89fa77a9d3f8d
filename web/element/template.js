// The markup of one designer, cloned into its shadow root. Parts (for ::part() styling) and the ids the
// panels bind to (ui.js and the modules it composes) live here; styles in element.css. Which pieces show
// depends on the host's `controls` and `readonly` attributes (element.css); data-overflow ranks the toolbar
// items that leave a full row for the ⋯ menu, lowest first (toolbar-overflow.js).

// Titles too long for a line of the markup (the text each element shows on hover).
const TITLES = {
  panels: 'Show or hide the settings and constraint panels (on small screens they are drawers)',
  exportField: 'Download the solved field: per-edge one-form, per-face and per-vertex vectors, singularities',
  strength: 'How strong the field is: along a stroke its size; for a source or sink the total flow out or in; for ' +
    'a vortex how fast it turns (above 0)',
  weight: 'How strictly the field follows the stroke or vector: loosely (weight 1e2), closely (1e4) or exactly (1e6)',
  boundary: 'How the field meets the open edges of the mesh: free, along them (tangential), across them (normal) or ' +
    'at a fixed angle',
  symmetry: 'What the field is made of. Vector: flows, directions with a sign. Line: a direction without sign, for ' +
    'anisotropic materials (hair, brushed metal, wood grain, KHR_materials_anisotropy). Cross: four directions at ' +
    'right angles, for weaves, tiles, bricks and quad remeshing. Line and cross fields have no sources, sinks or ' +
    'vortices: switching removes them (undo restores them)',
  curvature: 'Pulls the field toward principal curvature directions: the usual start for quad remeshing and hatching',
  curvatureStrength: 'How strongly the field turns toward the curvature directions where nothing you drew says ' +
    'otherwise',
  gamma: "How gently the field's size fades away from what you drew: 0 = quickly (plain Laplacian), larger = more " +
    'gently (bi-Laplacian term γ)',
  component: 'The part of the Hodge decomposition c = dα + δβ + h that the arrows, streamlines, flow texture, ' +
    "magnitude colours and texture draw (in the whole field's magnitude scale); singularity markers stay the whole " +
    "field's",
  singularity: 'Click a vertex: a prescribed singularity of the index chosen beside; drag one to move it, drag ' +
    'from empty surface for a +/− pair; Delete removes the selected one (I)',
  singularityIndex: "The index of the singularity a click places, a multiple of 1/N (N: the field's symmetry)",
  feature: 'Click or drag along edges: sharp features the field follows (Alt or Shift: remove them) (K)',
  featureAngle: 'Edges where the surface folds by more than this many degrees are sharp features the field ' +
    'follows (0: none; a new design starts at 35 on a creased model, at 0 on a curved one made of facets; the ' +
    'Feature tool adds or removes edges)',
  exactSingularities: 'The field has exactly the singularities you prescribe, and none where you prescribe ' +
    'none (a torus then has none; on a sphere the field places what the prescribed ones leave out)',
  shares: "Share of the energy in each part: ‖part‖² / ‖c‖² in the decomposition's inner product",
};

// The first-visit hint over the view.
const HINT = 'Drag to turn the model · double-click to orbit around a point · ' +
  'pick <b>Stroke</b> and drag across the surface to steer the field · <b>?</b> for help';

export const TEMPLATE = `<div class="root" part="root">
  <header class="toolbar" part="toolbar" role="toolbar" aria-label="Design tools">
    <span class="brand" part="brand" data-overflow="0" data-overflow-reserve>Tangent-field designer</span>
    <button id="panels-toggle" type="button" part="panels-toggle" aria-expanded="false"
      aria-controls="side-panel constraints-panel" title="${TITLES.panels}">☰ Panels</button>
    <div class="group" role="group" aria-label="Files">
      <button id="open-button" type="button" class="edit" data-overflow="5"
        title="Open a mesh (.glb, .gltf, .obj, .off, .ply) — or drop one on the view">Open…</button>
      <input id="file-input" type="file" hidden>
      <button id="save-design" type="button" data-overflow="7"
        title="Save the design as JSON, the format &quot;tvf design&quot; reads (Ctrl+S)">Save</button>
      <button id="load-design" type="button" class="edit" data-overflow="4"
        title="Load a design JSON (or drop one on the view)">Load…</button>
      <input id="design-input" type="file" accept=".json,application/json" hidden>
      <button id="export-field" type="button" data-overflow="6" title="${TITLES.exportField}">Export</button>
    </div>
    <span class="sep" aria-hidden="true"></span>
    <div class="segmented" role="group" aria-label="Tool">
      <button type="button" data-tool="orbit" aria-pressed="true" title="Orbit, pan, zoom (O)">Orbit</button>
      <button type="button" data-tool="select" aria-pressed="false"
        title="Select a constraint handle to edit or delete it (E)">Select</button>
      <button type="button" class="edit" data-tool="stroke" aria-pressed="false"
        title="Draw strokes on the surface (S)">Stroke</button>
      <button type="button" class="edit" data-tool="vector" aria-pressed="false"
        title="Drag on a triangle: the field's direction and magnitude there (V)">Vector</button>
      <button type="button" class="edit" data-tool="source" aria-pressed="false"
        title="Click: a source at the nearest vertex (R)">Source</button>
      <button type="button" class="edit" data-tool="sink" aria-pressed="false"
        title="Click: a sink at the nearest vertex (G)">Sink</button>
      <button type="button" class="edit" data-tool="vortex" aria-pressed="false"
        title="Click: a vortex in the triangle — the field turns around it (B; X flips its turning)">Vortex</button>
      <button type="button" class="edit" data-tool="singularity" aria-pressed="false"
        title="${TITLES.singularity}">Singularity</button>
      <button type="button" class="edit" data-tool="feature" aria-pressed="false"
        title="${TITLES.feature}">Feature</button>
    </div>
    <span class="tool-options edit">
      <label data-for="stroke source sink vortex" title="${TITLES.strength}">Strength
        <input id="strength" type="number" value="1" min="0" step="0.1">
      </label>
      <label data-for="stroke vector" title="${TITLES.weight}">Follow
        <select id="weight">
          <option value="100">loosely</option>
          <option value="10000" selected>closely</option>
          <option value="1000000">exactly</option>
        </select>
      </label>
      <span class="segmented" data-for="vortex" role="group" aria-label="Vortex orientation">
        <button type="button" data-orientation="ccw" aria-pressed="true"
          title="Counter-clockwise about the surface normal (X flips)">↺ CCW</button>
        <button type="button" data-orientation="cw" aria-pressed="false"
          title="Clockwise about the surface normal (X flips)">↻ CW</button>
      </span>
      <label data-for="singularity" title="${TITLES.singularityIndex}">Index
        <select id="singularity-index"></select>
      </label>
      <span class="segmented" data-for="feature" role="group" aria-label="Feature edit">
        <button type="button" data-feature-mode="add" aria-pressed="true"
          title="Edges clicked or dragged along become features">Add</button>
        <button type="button" data-feature-mode="remove" aria-pressed="false"
          title="Edges clicked or dragged along stop being features (or hold Alt or Shift)">Remove</button>
      </span>
    </span>
    <span class="sep edit" aria-hidden="true"></span>
    <button id="undo" type="button" class="edit" title="Undo (Ctrl+Z)" aria-label="Undo" disabled>↶</button>
    <button id="redo" type="button" class="edit" title="Redo (Ctrl+Shift+Z)" aria-label="Redo" disabled>↷</button>
    <span class="sep" aria-hidden="true"></span>
    <button id="frame-button" type="button" data-overflow="2"
      title="Frame the model: bring all of it back into view (F or Home)">Frame</button>
    <button id="screenshot-button" type="button" data-overflow="1"
      title="Save a PNG picture of the view (twice the view's size)">Picture</button>
    <button id="more-button" type="button" aria-label="More" aria-haspopup="menu" aria-expanded="false"
      aria-controls="more-menu" title="More: the toolbar buttons that do not fit in this width" hidden>⋯</button>
    <button id="help-button" type="button" title="Help: every tool, shortcut and gesture (? , H or F1)"
      aria-label="Help">?</button>
    <div id="more-menu" role="menu" aria-label="More" hidden></div>
  </header>

  <div id="error-banner" part="error" role="alert" hidden>
    <span class="message"></span>
    <button type="button" class="action" hidden></button>
    <button type="button" class="dismiss" aria-label="Dismiss error">×</button>
  </div>

  <div id="viewport" part="viewport">
    <div id="progress" part="progress" role="progressbar" aria-label="Working" hidden><div class="bar"></div><span
      class="label"></span><button type="button" class="cancel"
      title="Stop this operation (Esc); the design comes back as it was before it">Cancel</button></div>
    <aside id="side-panel" part="panel side-panel" aria-label="Field settings and views">
      <details class="edit" open>
        <summary>Field</summary>
        <div id="boundary-row" hidden>
          <label title="${TITLES.boundary}">Boundary
            <select id="boundary">
              <option value="free" selected>free</option>
              <option value="tangential">tangential</option>
              <option value="normal">normal</option>
              <option value="angle">fixed angle</option>
            </select>
          </label>
          <label id="boundary-angle-row" hidden
            title="Angle from the boundary edge towards the interior, in degrees">Angle β°
            <input id="boundary-angle" type="number" value="45" step="5">
          </label>
        </div>
        <label title="${TITLES.symmetry}">Symmetry
          <select id="symmetry">
            <option value="1" selected>Vector</option>
            <option value="2">Line</option>
            <option value="4">Cross</option>
            <option id="symmetry-other" value="" hidden></option>
          </select>
        </label>
        <div id="curvature-row" title="${TITLES.curvature}">
          <label class="check"><input id="curvature-align" type="checkbox"> Align to curvature</label>
          <label class="sub" title="${TITLES.curvatureStrength}">Strength <input id="curvature-strength" type="number"
            value="1" min="0" step="0.1"></label>
        </div>
        <label title="${TITLES.gamma}">Smoothness γ
          <input id="gamma" type="number" value="0" min="0" step="0.1">
        </label>
        <label title="${TITLES.featureAngle}">Feature angle°
          <input id="feature-angle" type="number" value="35" min="0" max="180" step="5">
        </label>
        <label class="check" title="${TITLES.exactSingularities}"><input id="exact-singularities"
          type="checkbox"> Only prescribed singularities</label>
        <p id="feature-count" class="note" hidden></p>
        <p id="singularity-summary" class="note" hidden></p>
        <p class="note">Changing symmetry, smoothness<span id="boundary-note"
          hidden> or the boundary</span> rebuilds the solver: a moment on large models.</p>
      </details>
      <details open>
        <summary>Views</summary>
        <label class="check"><input id="show-arrows" type="checkbox" checked> Arrows</label>
        <div class="sub">
          <label title="Arrow density: spacing on screen, the same at any mesh resolution and zoom">Density <input
            id="arrow-density" type="range" min="1" max="10" step="1" value="6"></label>
          <label class="check" title="Arrow length proportional to the magnitude"><input id="arrow-scaled"
            type="checkbox"> by magnitude</label>
        </div>
        <label class="check"><input id="show-streamlines" type="checkbox"> Streamlines</label>
        <div class="sub">
          <label title="Distance between streamlines">Spacing <input id="streamline-spacing" type="range" min="1"
            max="10" step="1" value="5"></label>
        </div>
        <label class="check"
          title="Flow texture: white noise smeared along the field (line integral convolution), drawn on the GPU"><input
          id="show-lic" type="checkbox"> Flow texture</label>
        <label class="check"><input id="show-colormap" type="checkbox"> Magnitude colours</label>
        <div id="legend" hidden title="Magnitude (arrow and surface colours, viridis)"><span>0</span><span
          class="ramp"></span><span id="legend-max"></span></div>
        <label class="check"><input id="show-singularities" type="checkbox"> Singularities</label>
        <label title="${TITLES.component}">Component
          <select id="view-component">
            <option value="whole" selected>Whole field</option>
            <option value="exact">Curl-free (gradient)</option>
            <option value="coexact">Divergence-free (rotation)</option>
            <option value="harmonic">Harmonic</option>
          </select>
        </label>
        <p id="component-shares" class="note" hidden title="${TITLES.shares}">Energy: curl-free <span
          data-share="exact">–</span> · divergence-free <span data-share="coexact">–</span> · harmonic <span
          data-share="harmonic">–</span></p>
      </details>
    </aside>
    <aside id="constraints-panel" part="panel constraints-panel" aria-label="Constraints">
      <h2>Constraints <button id="clear-all" type="button" class="edit"
        title="Remove every constraint (undoable)">Clear</button></h2>
      <ul id="constraint-list"></ul>
      <p id="constraints-empty">None yet. Choose <b>Stroke</b> and drag across the model.</p>
      <section id="selection-panel" aria-label="Selected constraint" hidden>
        <h3 id="selection-title"></h3>
        <label id="sel-weight-row">Weight <input id="sel-weight" type="number" min="0" step="any"></label>
        <label id="sel-strength-row">Strength <input id="sel-strength" type="number" step="any"></label>
        <button id="sel-delete" type="button" class="edit"
          title="Delete the selected constraint (Delete)">Delete</button>
      </section>
    </aside>
    <div id="confirm" part="confirm" role="alertdialog" aria-modal="true" aria-labelledby="confirm-message" hidden>
      <p id="confirm-message"></p>
      <div class="buttons"><button id="confirm-cancel" type="button">Cancel</button> <button id="confirm-ok"
        type="button" class="primary"></button></div>
    </div>
    <div id="view-presets" part="view-presets" role="group" aria-label="View">
      <button type="button" data-view="front" title="Front view (1)">Front</button>
      <button type="button" data-view="side" title="Side view (3)">Side</button>
      <button type="button" data-view="top" title="Top view (7)">Top</button>
    </div>
    <div id="hint" part="hint" hidden>
      <span>${HINT}</span>
      <button type="button" class="close" aria-label="Dismiss the hint">×</button>
    </div>
    <div id="help" part="help" role="dialog" aria-label="Help" hidden>
      <div class="help-head"><h2>Help</h2><button type="button" class="close" aria-label="Close help">×</button></div>
      <div class="help-body"></div>
    </div>
    <div id="drop-overlay" hidden>Drop a mesh to load it, or a design (.json)</div>
  </div>

  <footer id="status" part="status" aria-live="polite">Loading…</footer>
</div>`;
