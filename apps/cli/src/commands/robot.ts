import { InvalidArgumentError, type Command } from 'commander';
import { IMPORT_NAME, planImport } from '@armtwin/robot';
import { importSource, RobotExistsError, writeRobotFolder } from '@armtwin/robot/import-node';
import { MODELS_DIR } from '@armtwin/sim';
import { registerRobotCalibration } from './robot-calibration.ts';

interface ImportFlags {
  name?: string;
  models: string;
  force: boolean;
}

function profileName(value: string): string {
  if (!IMPORT_NAME.test(value)) throw new InvalidArgumentError('must be [a-z0-9_-]{1,32}');
  return value;
}

export function registerRobot(program: Command): void {
  const robot = program
    .command('robot')
    .description('robot profiles: import a URDF, LeRobot calibrations in and out');
  registerRobotCalibration(robot);
  robot
    .command('import')
    .description(
      'import a robot as it comes: a .urdf, a folder or a .zip holding one → <models>/NAME/ (URDF, meshes, profile.json)',
    )
    .argument('<source>', 'a .urdf file, a folder holding one, or a .zip holding one')
    .option(
      '--name <name>',
      "the profile's name (default: from the URDF's robot name)",
      profileName,
    )
    .option('--models <dir>', 'the folder of robot profiles', MODELS_DIR)
    .option('--force', 'replace an existing profile of that name', false)
    .addHelpText(
      'after',
      `
Mesh paths (package://pkg/…, relative, file://) are resolved from the URDF's folder upwards and
rewritten relative to the new URDF; STL, OBJ and DAE meshes are copied under meshes/. The
profile is derived from the URDF (docs/robots.md, "Import your robot"): the chain to the tool
centre, limits, angle frames beyond 270°, mimic joints left to their leader. Polarity, offsets
and the bus are left for calibration. Refuses a URDF without movable joints, a missing visual
mesh or one it cannot read; warns about meshes too heavy for a page.`,
    )
    .action((source: string, flags: ImportFlags) => {
      const result = planImport(importSource(source), flags.name ? { name: flags.name } : {});
      if (!result.ok) throw new Error(`cannot import ${source}:\n  ${result.errors.join('\n  ')}`);
      const { plan } = result;
      let dir: string;
      try {
        dir = writeRobotFolder(plan, flags.models, flags.force);
      } catch (err) {
        if (!(err instanceof RobotExistsError)) throw err;
        throw new Error(`${err.message}: give another --name, or --force to replace it`, {
          cause: err,
        });
      }
      const say = (m: string) => process.stderr.write(`armtwin: ${m}\n`);
      for (const w of plan.warnings) say(`warning: ${w}`);
      for (const n of plan.profile.notes) say(n);
      process.stdout.write(
        `${JSON.stringify({ name: plan.name, dir, files: plan.files.length })}\n`,
      );
    });
}
