/**
 * `armtwin episode start|stop|discard|list`: an operator marks episodes of an arm's history
 * (docs/dataset.md) through the middleware's HTTP API (`/api/arms/<id>/episodes`), the same
 * route the HUD would use. Log-in: `--user name:password` (HTTP Basic) or `API_TOKEN` (reads).
 */
import { Argument, type Command } from 'commander';

interface EpisodeFlags {
  arm: string;
  api: string;
  task?: string;
  user?: string;
}

const ACTIONS = ['start', 'stop', 'discard', 'list'] as const;

export function registerEpisode(program: Command): void {
  program
    .command('episode')
    .description(
      "mark an episode of an arm's history (start with a task, stop, discard) or list them",
    )
    .addArgument(new Argument('<action>').choices(ACTIONS))
    .requiredOption('--arm <id>', 'arm id')
    .option('--task <text>', "start: what the episode shows, one line (LeRobot's single_task)")
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
  armtwin export --format lerobot --arm so101 --profile so101 --episodes all --out ds/`,
    )
    .action(async (action: (typeof ACTIONS)[number], f: EpisodeFlags, cmd: Command) => {
      if (action === 'start' && !f.task?.trim()) return cmd.error('start needs --task');
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
                body: JSON.stringify({ action, task: f.task }),
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
