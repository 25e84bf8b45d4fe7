// Runs the Khronos glTF Validator on one file and prints its errors, warnings and informations
// as JSON:
//   node validate.js VALIDATOR_MODULE_DIR FILE
// External resources (buffers, images) are read relative to FILE; a missing one is the
// validator's own IO_ERROR, as for any reader.
'use strict';
const fs = require('fs');
const path = require('path');
const [moduleDir, file] = process.argv.slice(2);
const validator = require(moduleDir);

validator
  .validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: path.basename(file),
    maxIssues: 0, // no limit
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        const resource = path.resolve(path.dirname(file), decodeURIComponent(uri));
        fs.readFile(resource, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
      }),
  })
  .then((report) => {
    // Severity 0 is an error, 1 a warning, 2 an information (such as UNUSED_OBJECT).
    const issues = report.issues.messages
      .filter((m) => m.severity <= 2)
      .map((m) => ({ code: m.code, severity: m.severity, pointer: m.pointer || '', message: m.message }));
    process.stdout.write(JSON.stringify({ truncated: report.issues.truncated, issues }) + '\n');
  })
  .catch((error) => {
    process.stderr.write(`validator failed on ${file}: ${error}\n`);
    process.exit(1);
  });
