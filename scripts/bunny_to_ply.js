// Converts the npm `bunny` package (exports.positions, exports.cells) to an ASCII PLY.
// Usage: node bunny_to_ply.js path/to/index.js out.ply
'use strict';
const fs = require('fs');
const [src, out] = process.argv.slice(2);
const mesh = require(require('path').resolve(src));
if (!Array.isArray(mesh.positions) || !Array.isArray(mesh.cells)) {
  console.error(`${src}: expected exports.positions and exports.cells`);
  process.exit(1);
}
const lines = [
  'ply', 'format ascii 1.0',
  'comment Stanford bunny (public domain), converted from the npm package "bunny" by Lucent',
  `element vertex ${mesh.positions.length}`,
  'property float x', 'property float y', 'property float z',
  `element face ${mesh.cells.length}`,
  'property list uchar int vertex_indices', 'end_header',
];
for (const p of mesh.positions) lines.push(p.join(' '));
for (const c of mesh.cells) {
  if (c.some((i) => !(i >= 0 && i < mesh.positions.length))) {
    console.error(`${src}: face index out of range`);
    process.exit(1);
  }
  lines.push(`${c.length} ${c.join(' ')}`);
}
fs.writeFileSync(out + '.tmp', lines.join('\n') + '\n');
fs.renameSync(out + '.tmp', out);
