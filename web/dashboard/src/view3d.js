// The 3D panel around Scene3D: a message in the panel says "no data yet" until the first scene arrives, and
// why there is no 3D view when the browser has no WebGL. Without WebGL the rest of the dashboard must work, so
// a stand-in with Scene3D's methods takes the messages and draws nothing.
import { Scene3D } from './scene3d.js';

class NoScene {
  constructor() {
    this.follow = true;
    this.webgl = false;
  }
  applySceneUpdate() {}
  applyPointCloud() {}
  setCar() {}
  removeTopic() {}
  topDown() {}
  counts() {
    return { topics: {}, points: 0, frames: 0, webgl: false };
  }
}

export function createView3D(container, messageEl) {
  const say = (text, kind) => {
    messageEl.textContent = text;
    messageEl.className = `view3d-message ${kind}`;
    messageEl.hidden = !text;
  };
  let scene;
  try {
    scene = new Scene3D(container);
    scene.webgl = true;
    say('no data yet', 'waiting');
  } catch (e) {
    console.warn('3D view unavailable:', e);
    scene = new NoScene();
    say('3D view unavailable: this browser gives the page no WebGL (enable hardware acceleration or WebGL). ' +
        'Everything else works.', 'unavailable');
  }
  // Hides "no data yet" at the first scene message; the unavailable message stays.
  const sceneArrived = () => {
    if (scene.webgl && !messageEl.hidden) say('', 'waiting');
  };
  return { scene, sceneArrived };
}
