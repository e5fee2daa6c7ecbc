import { InvalidArgumentError, type Command } from 'commander';
import { IK_CODES, solveIk } from '@armtwin/ik';

function finite(name: string) {
  return (value: string): number => {
    const n = Number(value);
    if (value.trim() === '' || !Number.isFinite(n)) {
      throw new InvalidArgumentError(`${name} must be a number, got ${JSON.stringify(value)}`);
    }
    return n;
  };
}

export function registerIk(program: Command): void {
  program
    .command('ik')
    .description('solve the 5-axis IK for a gripper target (mm) and print the result as JSON')
    .argument('<x>', 'target x, mm', finite('x'))
    .argument('<y>', 'target y, mm', finite('y'))
    .argument('<z>', 'target z, mm', finite('z'))
    .argument(
      '[alpha]',
      'gripper pitch from horizontal, degrees (omit to search −90…90)',
      finite('alpha'),
    )
    .addHelpText(
      'after',
      `
Prints {"code", "message", "alpha", "pwm" (servos 000–003, when code is 0), …} and exits 0
whatever the code. Negative numbers work: armtwin ik -- -120 80 40 -90  or  armtwin ik 0 -150 60`,
    )
    .action((x: number, y: number, z: number, alpha: number | undefined) => {
      const result = solveIk(x, y, z, alpha);
      const out = {
        code: result.code,
        message: IK_CODES[result.code as keyof typeof IK_CODES] ?? 'unknown',
        target: { x, y, z },
        alpha: result.alpha,
        ...(result.code === 0
          ? { joints: result.joints, servoAngles: result.servoAngles, pwm: result.pwm }
          : {}),
      };
      process.stdout.write(JSON.stringify(out) + '\n');
    });
}
