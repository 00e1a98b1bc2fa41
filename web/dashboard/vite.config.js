// Vite build of the pit-lane dashboard. Relative asset paths so the daemon can serve dist/ from any root;
// everything is bundled (no CDN, no web fonts): the page makes no request beyond its own server.
import { defineConfig } from 'vite';

export default defineConfig({
  base: './',
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    target: 'es2022',
    chunkSizeWarningLimit: 1500,
    sourcemap: false,
  },
  server: {
    // `npm run dev` against a running daemon: the page connects to ?ws=ws://host:8080/
    port: 5173,
  },
});
