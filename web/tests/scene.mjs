// A small glTF scene for the browser tests, made here rather than kept as a file: a floor, a
// back wall, a table (a slab on four legs) and a thin pillar in front of the wall, so the view
// has contact shadows, a crease, and geometry the depth buffer hides (under the table, behind the
// pillar). One mesh of boxes, positions and normals, buffer embedded as a data: URI, no camera
// (both the CLI and the page take the library's automatic one).

// Axis-aligned box from its min and max corners: 6 faces of 4 vertices, outward normals.
function box(min, max, positions, normals, indices) {
  const faces = [
    [[0, 1, 0], [[0, 1, 1], [1, 1, 1], [1, 1, 0], [0, 1, 0]]],
    [[0, -1, 0], [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]]],
    [[1, 0, 0], [[1, 0, 0], [1, 1, 0], [1, 1, 1], [1, 0, 1]]],
    [[-1, 0, 0], [[0, 0, 1], [0, 1, 1], [0, 1, 0], [0, 0, 0]]],
    [[0, 0, 1], [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]],
    [[0, 0, -1], [[1, 0, 0], [0, 0, 0], [0, 1, 0], [1, 1, 0]]],
  ];
  for (const [normal, corners] of faces) {
    const base = positions.length / 3;
    for (const c of corners) {
      positions.push(...c.map((t, i) => (t ? max[i] : min[i])));
      normals.push(...normal);
    }
    indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
  }
}

export function tableScene() {
  const positions = [], normals = [], indices = [];
  box([-2, -0.1, -2], [2, 0, 2], positions, normals, indices); // floor
  box([-2, 0, -2], [2, 2, -1.9], positions, normals, indices); // back wall
  box([-0.8, 0.7, -0.5], [0.8, 0.76, 0.5], positions, normals, indices); // table top
  for (const [x, z] of [[-0.75, -0.45], [0.7, -0.45], [-0.75, 0.4], [0.7, 0.4]]) {
    box([x, 0, z], [x + 0.05, 0.7, z + 0.05], positions, normals, indices); // legs
  }
  box([1.2, 0, -1.5], [1.3, 1.6, -1.4], positions, normals, indices); // pillar before the wall
  const pos = new Float32Array(positions), nrm = new Float32Array(normals), idx = new Uint32Array(indices);
  const bytes = Buffer.concat([Buffer.from(pos.buffer), Buffer.from(nrm.buffer), Buffer.from(idx.buffer)]);
  const min = [0, 1, 2].map((a) => Math.min(...positions.filter((_, i) => i % 3 === a)));
  const max = [0, 1, 2].map((a) => Math.max(...positions.filter((_, i) => i % 3 === a)));
  const gltf = {
    asset: { version: '2.0', generator: 'obscura web tests' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0, name: 'table-room' }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1 }, indices: 2 }] }],
    buffers: [{ byteLength: bytes.length, uri: `data:application/octet-stream;base64,${bytes.toString('base64')}` }],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: pos.byteLength, target: 34962 },
      { buffer: 0, byteOffset: pos.byteLength, byteLength: nrm.byteLength, target: 34962 },
      { buffer: 0, byteOffset: pos.byteLength + nrm.byteLength, byteLength: idx.byteLength, target: 34963 },
    ],
    accessors: [
      { bufferView: 0, componentType: 5126, count: pos.length / 3, type: 'VEC3', min, max },
      { bufferView: 1, componentType: 5126, count: nrm.length / 3, type: 'VEC3' },
      { bufferView: 2, componentType: 5125, count: idx.length, type: 'SCALAR' },
    ],
  };
  return JSON.stringify(gltf);
}
