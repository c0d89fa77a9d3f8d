// Worker half of mesh-bvh-transfer.test.mjs: builds the serialized BVH off the main thread, as the core worker
// does, and posts it back with its transfer list (a real postMessage, which throws on a buffer listed twice).
import { parentPort, workerData } from 'node:worker_threads';
import { buildSerializedBVH, float32Arrays, transferList } from '../../web/geometry/mesh-bvh-transfer.js';

const { positions, triangles, normals } = workerData;
const bvh = buildSerializedBVH(positions, triangles);
const float32 = float32Arrays(normals, bvh);
parentPort.postMessage({ bvh, float32 }, transferList(bvh, float32));
