// Runs the Khronos glTF-Validator on one file; prints its issue counts as JSON.
//   node gltf_validate.js VALIDATOR_DIR FILE
const fs = require('fs');
const validator = require(process.argv[2]);
const file = process.argv[3];
validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {uri: file})
    .then((r) => {
      const i = r.issues;
      console.log(JSON.stringify({
        errors: i.numErrors,
        warnings: i.numWarnings,
        infos: i.numInfos,
        messages: i.messages.slice(0, 10).map((m) => m.code + ' ' + m.pointer),
      }));
    })
    .catch((e) => {
      console.error(String(e));
      process.exit(3);
    });
