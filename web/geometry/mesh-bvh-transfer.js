// The surface's three-mesh-bvh bounds tree and draw arrays, built in the core worker and handed to the page,
// so that taking a model on costs the page's thread no O(n) pass (issue 28: ~800k-triangle scans blocked it
// for seconds, mostly in `new MeshBVH` and in Float64→Float32 copies).
//
// Worker side (no DOM: three's BufferGeometry and three-mesh-bvh's builder run in a worker):
//   const bvh = buildSerializedBVH(mesh.positions, mesh.triangles);
//   const float32 = float32Arrays(surface.vertexNormals, bvh);
//   post { …, surface: { ...surface.arrays(), bvh, float32 } } with transferList(bvh, float32) added to the
//   transfer list. Surface.fromArrays() keeps unknown keys, so the page's Surface carries `bvh` and `float32`.
// Page side: viewer.setMesh(surface) draws from those arrays and calls adoptBVH() instead of building.
// A big model's surface comes in two messages (pageSurface with picking false, then pickingParts): drawable
// first, its adjacency, face normals and BVH (without positions or index, adopted onto the drawn geometry)
// after its first field.
//
// SerializedMeshBVH (what buildSerializedBVH returns; a plain, structured-cloneable object):
//   version, roots, index, indirectBuffer  three-mesh-bvh's SerializedBVH (MeshBVH.serialize, indirect mode):
//       roots: ArrayBuffer[] (the packed nodes), index: Uint32Array (3 per face, the core's triangles, in the
//       core's face order: indirect mode never reorders it), indirectBuffer: Uint32Array | Uint16Array (the
//       BVH's leaf order → face index, which is what keeps hit.faceIndex the core's face).
//   positions       Float32Array (3 per vertex): the position attribute the bounds were computed on.
//   boundingSphere  [cx, cy, cz, r]: three's computeBoundingSphere() of `positions`, done here so the page
//       need not walk the vertices again (the camera frames the model on it).
//   faces, vertices counts, to check the geometry it is adopted onto.
//
// Float32Mesh (surface.float32, optional): { positions: Float32Array (3/vertex), normals: Float32Array
//   (3/vertex, the Surface's area-weighted vertex normals), index: Uint32Array (3/face), colors:
//   Uint8Array (3/vertex, all 255, normalized: the colour map's attribute, written by viewer.setVertexField) }.
//   With a bvh, positions and index are the bvh's own arrays (the same objects: structured cloning keeps that identity,
//   and transferList() lists each buffer once, since a buffer listed twice makes postMessage throw).
import { BufferAttribute, BufferGeometry, Box3, Sphere, Vector3 } from 'three';
import { MeshBVH } from 'three-mesh-bvh';
import { faceNormals, halfEdgeNeighbours, vertexFaceMap } from './mesh-geometry.js';

// Bumped when the object's shape changes; adoptBVH refuses others (a stale cache would otherwise mis-hit).
export const SERIALIZED_MESH_BVH_VERSION = 1;

// positions: Float64Array (3 per vertex), triangles: Int32Array (3 per face), as the core gives them.
// options: three-mesh-bvh build options (strategy, targetLeafSize, …); `indirect` is always on.
export function buildSerializedBVH(positions, triangles, options = {}) {
  if (positions.length % 3 || triangles.length % 3) throw new Error('buildSerializedBVH: not 3 values per item');
  // `new Float32Array(typedArray)` is the engine's bulk conversion; Float32Array.from() walks an iterator.
  const position = new Float32Array(positions);
  const index = new Uint32Array(triangles);
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(position, 3));
  geometry.setIndex(new BufferAttribute(index, 1));
  // indirect: the default build reorders the index buffer in place, and then hit.faceIndex (and the drawn
  // triangle order) would no longer be the core's face. Indirect mode sorts a separate face list instead.
  const bvh = new MeshBVH(geometry, { verbose: false, ...options, indirect: true });
  geometry.computeBoundingSphere();
  const { center, radius } = geometry.boundingSphere;
  // cloneBuffers false: this BVH is thrown away after, so its buffers can be sent as they are (no copy), and
  // the serialized index is then `index` itself rather than a second copy of it.
  const serialized = MeshBVH.serialize(bvh, { cloneBuffers: false });
  return {
    version: serialized.version,
    roots: serialized.roots,
    index: serialized.index,
    indirectBuffer: serialized.indirectBuffer,
    format: SERIALIZED_MESH_BVH_VERSION,
    positions: position,
    boundingSphere: [center.x, center.y, center.z, radius],
    faces: triangles.length / 3,
    vertices: positions.length / 3,
  };
}

// The Float32 draw arrays of a mesh (worker side). vertexNormals: Float64Array (3 per vertex), e.g. the
// Surface's. bvh: a SerializedMeshBVH whose positions and index are shared rather than converted again;
// without one, positions and triangles (Float64Array, Int32Array) are needed.
export function float32Arrays(vertexNormals, bvh = null, positions = null, triangles = null) {
  return {
    positions: bvh?.positions ?? new Float32Array(positions),
    normals: new Float32Array(vertexNormals),
    index: bvh?.index ?? new Uint32Array(triangles),
    // The colour map's vertex colours (bytes, normalized: a quarter of the upload after every field change),
    // white until a field is shown: allocating and filling them on the page measured up to tens of ms there,
    // here it is free for the page.
    colors: new Uint8Array(vertexNormals.length).fill(255),
  };
}

// Every ArrayBuffer under the given objects (SerializedMeshBVH, Float32Mesh, …), each once: postMessage throws
// a DataCloneError on a buffer listed twice, and the bvh and the Float32Mesh share two. SharedArrayBuffers are
// shared, not transferred, so they are left out.
export function transferList(...objects) {
  const out = new Set();
  const visit = (x) => {
    if (x == null || typeof x !== 'object') return;
    if (x instanceof ArrayBuffer) out.add(x);
    else if (ArrayBuffer.isView(x)) visit(x.buffer);
    else if (Array.isArray(x)) x.forEach(visit);
    else if (Object.getPrototypeOf(x) === Object.prototype) Object.values(x).forEach(visit);
  };
  objects.forEach(visit);
  return [...out];
}

// Page side: puts the serialized BVH on `geometry` as geometry.boundsTree (no rebuild) and returns it.
// The geometry's position attribute, when it has one, must hold serialized.positions' values (the bounds were
// computed on them); when it has none, serialized.positions becomes it. The index becomes serialized.index
// itself: deserialize() would otherwise copy it element by element into whatever index array the geometry
// has, which is the O(n) pass this avoids, and a different index would not match the tree's leaves anyway.
// Sets geometry.boundingBox and boundingSphere when absent, from the tree's root and the worker's sphere.
export function adoptBVH(geometry, serialized) {
  if (serialized?.format !== SERIALIZED_MESH_BVH_VERSION || !serialized.indirectBuffer)
    throw new Error('adoptBVH: not an indirect SerializedMeshBVH of this version');
  const { positions, index, faces, vertices } = serialized;
  // Without positions and index (pickingParts): the geometry's own, which must then be there.
  const own = positions == null && index == null;
  if (
    own
      ? !geometry.index || geometry.index.count !== 3 * faces
      : index.length !== 3 * faces || positions.length !== 3 * vertices
  )
    throw new Error('adoptBVH: serialized arrays do not match their counts');
  const position = geometry.getAttribute('position');
  if (!position && !own) geometry.setAttribute('position', new BufferAttribute(positions, 3));
  else if (position?.count !== vertices || position.itemSize !== 3)
    throw new Error(`adoptBVH: the geometry has ${position?.count ?? 0} vertices, the BVH ${vertices}`);
  if (!own && geometry.index?.array !== index) geometry.setIndex(new BufferAttribute(index, 1));
  // indirect follows from indirectBuffer; setIndex finds geometry.index.array === index and copies nothing.
  const bvh = MeshBVH.deserialize(serialized, geometry, { setIndex: !own });
  geometry.boundsTree = bvh;
  // Both as a fresh build would leave them: MeshBVH's build sets the box from its root bounds.
  geometry.boundingBox ??= bvh.getBoundingBox(new Box3());
  if (!geometry.boundingSphere) {
    const [x, y, z, r] = serialized.boundingSphere;
    geometry.boundingSphere = new Sphere(new Vector3(x, y, z), r);
  }
  return bvh;
}

// A Surface's arrays for the page (Surface.fromArrays), with what the page would otherwise build on its own
// thread: the ray-casting BVH (~0.5 s at 800k faces) and the Float32 drawing arrays. Returns {arrays, list (the
// buffers to transfer)}. own: the caller keeps no use of the surface, so its own arrays go rather than copies
// (~0.7 s at 800k faces). picking false: without the adjacency, the face normals and the BVH (~1.2 s at 832k
// faces in the worker), which follow with pickingParts(): a big model's first field needs none of them, only
// its strokes do; arrays.pickingFollows says so, and float32.boundingSphere stands in for the BVH's.
export function pageSurface(surface, own = false, { picking = true } = {}) {
  const keys = surface.constructor.ARRAYS.filter((key) => picking || !surface.constructor.PICKING.includes(key));
  const arrays = { meanEdge: surface.meanEdge, centre: surface.centre, radius: surface.radius, area: surface.area };
  for (const key of keys) arrays[key] = own ? surface[key] : surface[key].slice();
  if (picking) {
    arrays.bvh = buildSerializedBVH(surface.positions, surface.triangles);
    arrays.float32 = float32Arrays(surface.vertexNormals, arrays.bvh);
  } else {
    arrays.float32 = float32Arrays(surface.vertexNormals, null, surface.positions, surface.triangles);
    Object.assign(arrays.float32, boundsOf(arrays.float32.positions));
    arrays.pickingFollows = true;
  }
  return { arrays, list: [...keys.map((key) => arrays[key].buffer), ...transferList(arrays.bvh, arrays.float32)] };
}

// What a surface sent with picking false lacks (Surface.adoptPicking): the adjacency, the face normals and the
// serialized BVH without the positions and index the page already draws from (adoptBVH takes the geometry's
// own). positions, triangles: the mesh's (views of the wasm heap will do: nothing here calls into it); keptBVH:
// value.bvh of an earlier call on this very mesh, or null to build it; adjacency: the same parts but the BVH
// as the core derives them from its own topology (designer.pendingFaceAdjacency(): {neighbour, vertexFaceStart,
// vertexFaces, normals}, arrays of their own), or null to derive them here. Returns {value, list}.
export function pickingParts(positions, triangles, keptBVH = null, adjacency = null) {
  const nV = positions.length / 3;
  const neighbour = adjacency?.neighbour ?? halfEdgeNeighbours(triangles, nV);
  const round = adjacency ? null : vertexFaceMap(triangles, nV);
  const vertexFaceStart = adjacency?.vertexFaceStart ?? round.start;
  const vertexFaces = adjacency?.vertexFaces ?? round.faces;
  const normals = adjacency?.normals ?? faceNormals(positions, triangles);
  const bvh = keptBVH ?? { ...buildSerializedBVH(positions, triangles), positions: null, index: null };
  const value = { neighbour, vertexFaceStart, vertexFaces, normals, bvh };
  return { value, list: transferList(value) };
}

// three's computeBoundingSphere() of a position array (the box's centre, the farthest point's distance) and
// computeBoundingBox(), which the page would otherwise run over the positions in the task that draws the first
// field (the surface layer's screen rectangle: 39-42 ms at 416k vertices in a profile).
function boundsOf(positions) {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(positions, 3));
  geometry.computeBoundingSphere();
  geometry.computeBoundingBox();
  const { center, radius } = geometry.boundingSphere;
  const { min, max } = geometry.boundingBox;
  return { boundingSphere: [center.x, center.y, center.z, radius], boundingBox: [...min, ...max] };
}
