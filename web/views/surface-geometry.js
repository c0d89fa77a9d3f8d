// The surface's three.js geometry, made from a Surface (geometry/surface.js) for viewer.js: the arrays the
// worker handed over where it made them (a big model's Float32 copies and bounds tree), else copies of the
// Surface's. Owns nothing; imports three, three-mesh-bvh and geometry/mesh-bvh-transfer.js.
import { Box3, BufferAttribute, BufferGeometry, Sphere, Vector3 } from 'three';
import { MeshBVH } from 'three-mesh-bvh';
import { adoptBVH } from '../geometry/mesh-bvh-transfer.js';

// The surface's BufferGeometry: position, normal and colour per vertex, the core's triangles as the index, and
// the bounds tree for picking.
export function meshGeometry(surface) {
  const { bvh = null, float32 = null } = surface;
  const positions = bvh?.positions ?? float32?.positions ?? new Float32Array(surface.positions);
  const normals = float32?.normals ?? new Float32Array(surface.vertexNormals);
  const index = bvh?.index ?? float32?.index ?? new Uint32Array(surface.triangles);
  const geom = new BufferGeometry();
  geom.setAttribute('position', new BufferAttribute(positions, 3));
  geom.setAttribute('normal', new BufferAttribute(normals, 3));
  // The worker's all-white colours are handed over, not shared: setVertexField paints into them, and a later
  // setMesh of the same Surface (a re-attached element) must start white again. Bytes, normalized: a quarter
  // of the upload after each field change (5 → 1.25 MB at 416k vertices).
  const colors = float32?.colors ?? new Uint8Array(positions.length).fill(255);
  if (float32) float32.colors = null;
  geom.setAttribute('color', new BufferAttribute(colors, 3, true));
  geom.setIndex(new BufferAttribute(index, 1));
  if (bvh) adoptBVH(geom, bvh); // also sets the bounding sphere the worker computed
  else if (surface.pickingFollows) {
    // A big model's BVH comes after its first field (Surface.adoptPicking); #boundsTree adopts it then.
    const [x, y, z, r] = float32.boundingSphere;
    geom.boundingSphere = new Sphere(new Vector3(x, y, z), r);
    const box = float32.boundingBox;
    geom.boundingBox = new Box3(new Vector3(box[0], box[1], box[2]), new Vector3(box[3], box[4], box[5]));
  } else {
    geom.computeBoundingSphere();
    // indirect: the default build reorders the index buffer, and then hit.faceIndex no longer names the
    // core's face. Indirect mode leaves the triangles in place and reports original indices.
    geom.boundsTree = new MeshBVH(geom, { indirect: true });
  }
  return geom;
}
