/**
 * `armtwin episode start|stop|discard|cut|list`: an operator marks episodes of an arm's history
 * (docs/dataset.md) through the middleware's HTTP API (`/api/arms/<id>/episodes`), the same
 * route the HUD's History panel uses. `cut` marks a past range (`--from`, `--to`); `discard
 * --start` throws a stopped episode away. Log-in: `--user name:password` (HTTP Basic) or `API_TOKEN` (reads).
 */
import { Argument, type Command } from 'commander';

interface EpisodeFlags {
  arm: string;
  api: string;
  task?: string;
  from?: string;
  to?: string;
  start?: string;
  user?: string;
}

const ACTIONS = ['start', 'stop', 'discard', 'cut', 'list'] as const;

export function registerEpisode(program: Command): void {
  program
    .command('episode')
    .description(
      "mark an episode of an arm's history (start with a task, stop, discard, cut a past range) or list them",
    )
    .addArgument(new Argument('<action>').choices(ACTIONS))
    .requiredOption('--arm <id>', 'arm id')
    .option('--task <text>', "start, cut: what the episode shows, one line (LeRobot's single_task)")
    .option('--from <time>', 'cut: where the episode starts (ISO 8601)')
    .option('--to <time>', 'cut: where it ends (ISO 8601)')
    .option(
      '--start <time>',
      'discard: the stopped episode that starts then (ISO 8601), not the recording one',
    )
    .option(
      '--api <url>',
      "the middleware's HTTP API",
      process.env.ARMTWIN_API ?? 'http://127.0.0.1:8080/api',
    )
    .option('--user <name:password>', 'log in (HTTP Basic); needed to mark where users are set')
    .addHelpText(
      'after',
      `
Example:
  armtwin episode start --arm so101 --task "pick up the red cube"
  armtwin episode stop --arm so101
  armtwin episode cut --arm so101 --task "wave" --from 2026-11-27T10:00:00Z --to 2026-11-27T10:00:20Z
  armtwin export --format lerobot --arm so101 --profile so101 --episodes all --out ds/`,
    )
    .action(async (action: (typeof ACTIONS)[number], f: EpisodeFlags, cmd: Command) => {
      if ((action === 'start' || action === 'cut') && !f.task?.trim())
        return cmd.error(`${action} needs --task`);
      if (action === 'cut' && !(f.from && f.to)) return cmd.error('cut needs --from and --to');
      const body =
        action === 'cut'
          ? { action, task: f.task, from: f.from, to: f.to }
          : action === 'discard' && f.start
            ? { action, start: f.start }
            : { action, task: f.task };
      const headers: Record<string, string> = { 'content-type': 'application/json' };
      if (f.user) headers.authorization = `Basic ${Buffer.from(f.user).toString('base64')}`;
      else if (process.env.API_TOKEN) headers.authorization = `Bearer ${process.env.API_TOKEN}`;
      const url = `${f.api.replace(/\/$/, '')}/arms/${encodeURIComponent(f.arm)}/episodes`;
      let res: Response;
      try {
        res =
          action === 'list'
            ? await fetch(url, { headers })
            : await fetch(url, {
                method: 'POST',
                headers,
                body: JSON.stringify(body),
              });
      } catch (err) {
        return cmd.error(`${url}: ${String((err as Error).cause ?? (err as Error).message)}`);
      }
      const answer = (await res.json().catch(() => ({}))) as { errors?: string[]; error?: string };
      if (!res.ok)
        return cmd.error(
          `armtwin episode ${action}: ${res.status} ${(answer.errors ?? [answer.error]).join('; ')}`,
        );
      process.stdout.write(`${JSON.stringify(answer)}\n`);
    });
}
