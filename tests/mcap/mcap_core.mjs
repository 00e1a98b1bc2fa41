// Loads @mcap/core (and fzstd) from the dashboard's node_modules, where the project's npm packages live; exits 77
// (CTest: skipped) when they are not installed.
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const dashboard = path.join(root, 'web/dashboard');
for (const pkg of ['@mcap/core', '@foxglove/crc', 'fzstd']) {
  if (!fs.existsSync(path.join(dashboard, 'node_modules', pkg))) {
    console.log(`skipped: ${pkg} not installed in web/dashboard/node_modules (npm ci there)`);
    process.exit(77);
  }
}
const requireDev = createRequire(path.join(dashboard, 'package.json'));
export const mcap = requireDev('@mcap/core');
export const { crc32, crc32Init, crc32Update, crc32Final } = requireDev('@foxglove/crc');
export const fzstd = requireDev('fzstd');
