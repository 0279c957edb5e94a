#!/usr/bin/env node
// Runs the Khronos glTF-Validator (npm package `gltf-validator`) on one .gltf / .glb file and
// prints its report as JSON on stdout (external .bin buffers are loaded from the file's folder).
//
// Usage: node validate_gltf.js <module-dir> <file>
//   <module-dir>  the installed package folder, e.g. <build>/node/node_modules/gltf-validator
//                 (installed with: npm install --prefix <build>/node gltf-validator@2.0.0-dev.3.10)
// Exit status: 0 = the validator ran (read numErrors / numWarnings from the report),
//              2 = usage error, the module or the file could not be loaded.
'use strict';
const fs = require('fs');
const path = require('path');

if (process.argv.length !== 4) {
    console.error('usage: node validate_gltf.js <gltf-validator module dir> <file.gltf|file.glb>');
    process.exit(2);
}
const moduleDir = path.resolve(process.argv[2]);
const file = path.resolve(process.argv[3]);

let validator;
try {
    validator = require(moduleDir);
} catch (e) {
    console.error('cannot load gltf-validator from ' + moduleDir + ': ' + e.message);
    process.exit(2);
}

let bytes;
try {
    bytes = fs.readFileSync(file);
} catch (e) {
    console.error('cannot read ' + file + ': ' + e.message);
    process.exit(2);
}

validator.validateBytes(new Uint8Array(bytes), {
    uri: path.basename(file),
    maxIssues: 0,  // report every issue
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
        const p = path.resolve(path.dirname(file), decodeURIComponent(uri));
        fs.readFile(p, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
    }),
}).then((report) => {
    process.stdout.write(JSON.stringify(report));
    process.exit(0);
}, (error) => {
    console.error('validator failed: ' + error);
    process.exit(2);
});
