/**
 * The 3D view's note of meshes that did not load: "2 meshes failed to load" with each file and
 * its reason, over the view, so a bad mesh is counted and named on the page while the rest of
 * the arm is drawn. Hidden when nothing failed.
 */
import type { MeshFailure } from './loadRobot.ts';

export class MeshFailureNote {
  readonly el: HTMLDivElement;

  constructor(container: HTMLElement) {
    this.el = document.createElement('div');
    this.el.dataset.testid = 'mesh-failures';
    this.el.setAttribute('role', 'status');
    Object.assign(this.el.style, {
      // Top centre: the one edge of the view that no panel covers.
      position: 'absolute',
      left: '50%',
      top: '8px',
      transform: 'translateX(-50%)',
      maxWidth: '40%',
      padding: '4px 8px',
      font: '12px system-ui, sans-serif',
      color: '#ffd6d6',
      background: 'rgba(90, 0, 0, 0.75)',
      borderRadius: '4px',
      pointerEvents: 'none',
      display: 'none',
    });
    container.appendChild(this.el);
  }

  show(failures: readonly MeshFailure[]): void {
    this.el.dataset.count = String(failures.length);
    this.el.replaceChildren();
    this.el.style.display = failures.length ? 'block' : 'none';
    if (!failures.length) return;
    const head = document.createElement('div');
    head.textContent = `${failures.length} mesh${failures.length === 1 ? '' : 'es'} failed to load`;
    this.el.appendChild(head);
    for (const f of failures) {
      const line = document.createElement('div');
      line.textContent = f.message.startsWith(f.url) ? f.message : `${f.url}: ${f.message}`;
      this.el.appendChild(line);
    }
  }
}
