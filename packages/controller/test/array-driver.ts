/** A driver of plain arrays for the core's tests: six servos at 1500 µs; a goal is reached `ms` after it is given. */
import type { ControllerDriver, Goal } from '../src/index.ts';

export class ArrayDriver implements ControllerDriver {
  at = new Array<number>(6).fill(1500);
  goals: { goal: Goal; t: number }[] = [];
  moves: Goal[][] = [];
  holds: number[][] = [];
  notReady = '';

  unready() {
    return this.notReady;
  }
  pose(t: number) {
    for (const { goal, t: t0 } of this.goals) if (t >= t0 + goal.ms) this.at[goal.i] = goal.pwm;
    return [...this.at];
  }
  moving(t: number) {
    return this.goals.some(({ goal, t: t0 }) => t < t0 + goal.ms);
  }
  move(goals: readonly Goal[], t: number) {
    this.moves.push([...goals]);
    for (const goal of goals) this.goals.push({ goal, t });
  }
  hold(indices: readonly number[], t: number) {
    this.pose(t);
    this.holds.push([...indices]);
    this.goals = [];
  }
  read(kind: 'position' | 'health', i: number) {
    return kind === 'position' ? { frame: `#00${i}P${this.at[i]}!` } : { refused: 'no health' };
  }
}
