#!/usr/bin/env node
// Runs the Khronos glTF-Validator (npm package gltf-validator, pinned in
// package.json) on each FILE, prints a summary and every reported issue, and
// exits non-zero when any file has an error or cannot be validated.
//
// Usage: node validate.js FILE...
'use strict';

const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

const SEVERITY = ['error', 'warning', 'info', 'hint'];

// GLB files carry their buffer, but a .gltf may reference neighbours.
function loaderFor(file) {
  return (uri) =>
    new Promise((resolve, reject) => {
      const target = path.resolve(path.dirname(file), decodeURIComponent(uri));
      fs.readFile(target, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
    });
}

async function validateFile(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0, // report everything
    writeTimestamp: false,
    externalResourceFunction: loaderFor(file),
  });
  const issues = report.issues;
  console.log(
    `${file}: numErrors=${issues.numErrors} numWarnings=${issues.numWarnings} ` +
      `numInfos=${issues.numInfos} numHints=${issues.numHints}`);
  for (const m of issues.messages) {
    console.log(`  ${SEVERITY[m.severity] || m.severity} ${m.code} ${m.pointer || ''} ${m.message}`);
  }
  if (report.info) {
    const info = report.info;
    console.log(`  generator=${info.generator} extensionsUsed=${JSON.stringify(info.extensionsUsed || [])} ` +
                `drawCallCount=${info.drawCallCount} totalVertexCount=${info.totalVertexCount} ` +
                `totalTriangleCount=${info.totalTriangleCount}`);
  }
  return issues.numErrors;
}

async function main(files) {
  if (files.length === 0) {
    console.error('usage: node validate.js FILE...');
    return 2;
  }
  console.log(`gltf-validator ${validator.version()}`);
  let failed = 0;
  for (const file of files) {
    try {
      if ((await validateFile(file)) > 0) failed += 1;
    } catch (error) {
      console.error(`${file}: cannot validate: ${error}`);
      failed += 1;
    }
  }
  return failed > 0 ? 1 : 0;
}

main(process.argv.slice(2)).then((code) => process.exit(code));
