#!/usr/bin/env node
// Every GLB that `tvf export` and the wasm FieldExporter write passes the Khronos glTF-Validator with 0
// errors, the page's exporter (wasm, over the mesh a Designer loaded) writes the same bytes as the CLI for the
// same mesh and one-form, and a GLB with a base-colour texture over UVs of its own has a vertex per (vertex, UV).
// Usage: node tests/node/export-validate.mjs [path/to/tvf] [path/to/tvf_core.mjs]
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import validator from 'gltf-validator';
import { GRID, diagonalStrokeDesign, patchGlb, patchOff } from './export-fixtures.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const tvf = resolve(process.argv[2] ?? join(ROOT, 'build/tvf'));
const modulePath = resolve(process.argv[3] ?? join(ROOT, 'build-wasm/tvf_core.mjs'));

let passed = 0, failed = 0;
// A 1x1 PNG: the smallest valid base-colour image.
const onePixelPng = () =>
  Uint8Array.from(atob('iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR4nGNoaPj/HwAFhgKZXtj7LQAAAABJRU5ErkJggg=='), (c) => c.charCodeAt(0));

function check(name, condition, detail = '') {
  if (condition) passed++;
  else failed++;
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${name}${!condition && detail ? `: ${detail}` : ''}`);
}

async function validate(name, bytes) {
  const report = await validator.validateBytes(new Uint8Array(bytes), {
    uri: name,
    maxIssues: 50,
    // Everything the exporter writes is inside the GLB; an external reference would be a defect.
    externalResourceFunction: (uri) => Promise.reject(new Error(`external resource ${uri}`)),
  });
  const errors = report.issues.messages.filter((m) => m.severity === 0);
  check(`${name}: glTF-Validator reports 0 errors (${report.issues.numWarnings} warnings, ${report.issues.numInfos} infos)`,
    report.issues.numErrors === 0, JSON.stringify(errors.slice(0, 5)));
  return report;
}

const dir = mkdtempSync(join(tmpdir(), 'tvf-export-'));
try {
  const files = {
    'patch.glb': patchGlb(),
    'normal-mapped.glb': patchGlb({ normalMap: true }),
    'patch.off': patchOff(),
    'design.json': JSON.stringify(diagonalStrokeDesign()),
  };
  for (const [name, data] of Object.entries(files)) writeFileSync(join(dir, name), data);
  const run = (...args) => execFileSync(tvf, args, { stdio: ['ignore', 'pipe', 'pipe'] });

  const outputs = {};
  for (const [model, extra] of [['patch.glb', []], ['normal-mapped.glb', []], ['patch.off', []],
    ['patch.glb', ['--strength', '0.6', '--rotation', '1.5707963', '--bits', '16', '--convention', 'opengl']]]) {
    const out = join(dir, `${model}.${extra.length ? 'options' : 'plain'}.glb`);
    run('export', join(dir, model), join(dir, 'design.json'), '--glb', out, '--size', '128', ...extra);
    outputs[out] = readFileSync(out);
    const report = await validate(`tvf export ${model} ${extra.join(' ')}`.trim(), outputs[out]);
    if (model === 'normal-mapped.glb') {
      const json = JSON.parse(new TextDecoder().decode(outputs[out].subarray(20, 20 + outputs[out].readUInt32LE(12))));
      const anisotropy = json.materials[0].extensions.KHR_materials_anisotropy;
      check('normal-mapped model: direction in anisotropyTexture, no TANGENT written',
        anisotropy.anisotropyTexture !== undefined && json.meshes[0].primitives[0].attributes.TANGENT === undefined);
    }
    check(`${model}: validator sees KHR_materials_anisotropy`, report.info.extensionsUsed.includes('KHR_materials_anisotropy'));
  }

  // Line and cross fields (the design's symmetry): the combed anisotropy GLB validates, on a model of its own
  // and a normal-mapped one, and the OFF patch rebuilt on a generated atlas.
  for (const symmetry of [2, 4]) {
    writeFileSync(join(dir, `design-${symmetry}.json`), JSON.stringify({ ...diagonalStrokeDesign(), symmetry }));
    for (const model of ['patch.glb', 'normal-mapped.glb', 'patch.off']) {
      const out = join(dir, `${model}.n${symmetry}.glb`);
      run('export', join(dir, model), join(dir, `design-${symmetry}.json`), '--glb', out, '--size', '128');
      const report = await validate(`tvf export ${model} (symmetry ${symmetry})`, readFileSync(out));
      check(`${model} (symmetry ${symmetry}): validator sees KHR_materials_anisotropy`,
        report.info.extensionsUsed.includes('KHR_materials_anisotropy'));
    }
  }

  // Stripes over a kept layout: the phase in the primitive's first free TEXCOORD_n, its vertices split round the
  // branch points of a vortex's stripes (the centre face of the patch's 16 x 16 grid).
  writeFileSync(join(dir, 'vortex.json'), JSON.stringify({ constraints: [{ type: 'vortex', face: 272, strength: 1 }] }));
  for (const model of ['patch.glb', 'normal-mapped.glb']) {
    const out = join(dir, `${model}.stripes.glb`);
    run('export', join(dir, model), join(dir, 'vortex.json'), '--glb', out, '--size', '128', '--stripes', '8');
    const bytes = readFileSync(out);
    const report = await validate(`tvf export ${model} --stripes (kept layout)`, bytes);
    const json = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + bytes.readUInt32LE(12))));
    const primitive = json.meshes[0].primitives[0];
    check(`${model} --stripes: the phase in TEXCOORD_1, named in the primitive's extras, vertices split ` +
      `(${report.info.totalVertexCount} for ${(GRID + 1) ** 2})`,
    primitive.attributes.TEXCOORD_1 !== undefined &&
      primitive.extras?.tangentFieldDesigner?.stripePhaseTexCoord === 1 &&
      report.info.totalVertexCount > (GRID + 1) ** 2);
  }

  // The wasm exporter as the page's worker drives it (web/core/core-export.js): the mesh the Designer loaded
  // (no second parse), the glTF document of the file, the CLI's one-form and embedded design -> the same bytes.
  const { default: createTvfCore } = await import(pathToFileURL(modulePath).href);
  const core = await createTvfCore();
  run('design', join(dir, 'patch.glb'), join(dir, 'design.json'), '-o', join(dir, 'field.json'));
  const oneForm = JSON.parse(readFileSync(join(dir, 'field.json'), 'utf8')).oneForm;
  const exporterFor = (bytes, format) => {
    const designer = new core.Designer();
    check(`wasm: the Designer loads ${format}`, designer.loadMesh(bytes, format) === '', designer.lastError());
    const exporter = new core.FieldExporter();
    const error = exporter.setMesh(designer.positions().slice(), designer.triangles().slice(), designer.cornerUVs().slice(),
      designer.sourceToWelded().slice()) || exporter.setSource(bytes, format);
    check(`wasm: the exporter takes the Designer's ${format} mesh`, error === '', error);
    const mesh = { positions: designer.positions().slice(), triangles: designer.triangles().slice() };
    designer.delete();
    return { exporter, mesh };
  };
  const { exporter } = exporterFor(files['patch.glb'], 'glb');
  check('wasm: own UVs are the atlas', exporter.atlasNote() === '');
  for (const [convention, bits] of [['gltf', 8], ['opengl', 16]]) {
    const png = join(dir, `flow-${convention}-${bits}.png`);
    run('export', join(dir, 'patch.glb'), join(dir, 'design.json'), '--flowmap', png, '--size', '96',
      '--convention', convention, '--bits', String(bits));
    const fromWasm = exporter.flowMapPng(oneForm, JSON.stringify({ size: 96, convention, bits }));
    check(`wasm flow map (${convention}, ${bits}-bit) has the CLI's bytes`,
      fromWasm && Buffer.compare(Buffer.from(fromWasm), readFileSync(png)) === 0, exporter.lastError());
  }
  const cliGlb = outputs[join(dir, 'patch.glb.plain.glb')];
  const design = core.embeddedDesignJson(cliGlb);
  check('wasm reads the design embedded in the CLI GLB', JSON.parse(design)?.constraints?.length === 1);
  const wasmGlb = exporter.glb(oneForm, design, JSON.stringify({ size: 128 }), null);
  check('wasm GLB has the CLI\'s bytes', wasmGlb && Buffer.compare(Buffer.from(wasmGlb), cliGlb) === 0,
    exporter.lastError());
  await validate('wasm FieldExporter patch.glb', wasmGlb);
  // Without UVs: the core's generated atlas, the same in the CLI and in wasm.
  const { exporter: offExporter, mesh: offMesh } = exporterFor(new TextEncoder().encode(files['patch.off']), 'off');
  check('wasm: a model without UVs says why it gets a generated atlas', /no texture coordinates/.test(offExporter.atlasNote()));
  run('export', join(dir, 'patch.off'), join(dir, 'design.json'), '--flowmap', join(dir, 'off.png'), '--size', '128');
  const offPng = offExporter.flowMapPng(oneForm, JSON.stringify({ size: 128 }));
  check('wasm flow map on a generated atlas has the CLI\'s bytes',
    offPng && Buffer.compare(Buffer.from(offPng), readFileSync(join(dir, 'off.png'))) === 0, offExporter.lastError());
  const offGlb = offExporter.glb(oneForm, '', JSON.stringify({ size: 128 }), null);
  await validate('wasm FieldExporter patch.off (generated atlas)', offGlb);
  // A base-colour texture over UVs of its own (as the page's synthesized texture): one file, a vertex per
  // (vertex, UV) pair. The UVs: the patch cut into two charts down its middle column.
  const nF = offMesh.triangles.length / 3;
  const uvs = new Float32Array(6 * nF);
  for (let c = 0; c < 3 * nF; c++) {
    const f = Math.floor(c / 3), v = offMesh.triangles[c];
    const cx = [0, 1, 2].reduce((x, k) => x + offMesh.positions[3 * offMesh.triangles[3 * f + k]], 0) / 3;
    const right = cx > 0.5;
    uvs[2 * c] = 0.02 + 0.45 * offMesh.positions[3 * v] + (right ? 0.5 : 0);
    uvs[2 * c + 1] = 0.02 + 0.96 * offMesh.positions[3 * v + 1];
  }
  const texturedGlb = offExporter.glb(oneForm, '', JSON.stringify({ size: 128 }), { png: onePixelPng(), cornerUVs: uvs });
  check('wasm: textured GLB written', !!texturedGlb, offExporter.lastError());
  const report = await validate('wasm FieldExporter patch.off with a base-colour texture', texturedGlb);
  const pairs = new Set(Array.from(offMesh.triangles, (v, c) => `${v} ${uvs[2 * c]} ${uvs[2 * c + 1]}`));
  const vertexCount = report.info.totalVertexCount;
  check(`textured GLB: a vertex per (vertex, UV) pair (${vertexCount} for ${pairs.size} pairs, ${3 * nF} corners)`, vertexCount === pairs.size);
  exporter.delete();
  offExporter.delete();
} finally {
  rmSync(dir, { recursive: true, force: true });
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
