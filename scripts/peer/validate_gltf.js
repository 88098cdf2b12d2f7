// Khronos' glTF-Validator (npm gltf-validator, installed by `make setup` into build-tools/) on a
// .gltf or .glb, external files read beside it. Prints the report's issues as JSON on stdout:
//   node scripts/peer/validate_gltf.js VALIDATOR_DIR FILE
// (VALIDATOR_DIR: build-tools/node_modules/gltf-validator). Exit 0 when the validator ran, 2 when it
// could not read the file.
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require(path.resolve(process.argv[2]));
const file = process.argv[3];

validator
  .validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: path.basename(file),
    maxIssues: 1000,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(data));
      }),
  })
  .then((report) => console.log(JSON.stringify(report.issues, null, 1)))
  .catch((err) => {
    console.error(`validate_gltf: ${file}: ${err}`);
    process.exit(2);
  });
