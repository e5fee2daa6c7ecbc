import { Command, CommanderError } from 'commander';
import { registerDecode } from './commands/decode.ts';
import { registerEpisode } from './commands/episode.ts';
import { registerExport } from './commands/export.ts';
import { registerIk } from './commands/ik.ts';
import { registerSim } from './commands/sim.ts';
import { registerGateway } from './commands/gateway.ts';
import { registerBroker } from './commands/broker.ts';
import { registerUp } from './commands/up.ts';
import { registerCamera } from './commands/camera.ts';
import { registerRobot } from './commands/robot.ts';
import { registerRos2 } from './commands/ros2.ts';
import { registerDeployMosquitto, registerPasswd } from './commands/security.ts';

/** Each command module adds itself to the program. */
const COMMANDS: ((program: Command) => void)[] = [
  registerDecode,
  registerExport,
  registerEpisode,
  registerIk,
  registerSim,
  registerGateway,
  registerBroker,
  registerUp,
  registerCamera,
  registerRobot,
  registerRos2,
  registerPasswd,
  registerDeployMosquitto,
];

export function buildProgram(): Command {
  const program = new Command('armtwin')
    .description('armtwin: a browser digital twin and control panel for servo-driven robot arms')
    .version('0.1.0')
    .showHelpAfterError('(run with --help for usage)')
    .configureOutput({ outputError: (text, write) => write(text) });
  for (const add of COMMANDS) add(program);
  return program;
}

export async function main(argv: string[]): Promise<void> {
  const program = buildProgram().exitOverride();
  try {
    await program.parseAsync(argv);
  } catch (error) {
    if (error instanceof CommanderError) {
      process.exitCode = error.exitCode;
      return;
    }
    process.stderr.write(`armtwin: ${error instanceof Error ? error.message : String(error)}\n`);
    process.exitCode = 1;
  }
}
