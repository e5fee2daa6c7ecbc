/**
 * Who may do what on the broker: the five roles as topic rules, and the matching
 * used by the embedded broker's hooks. The same table is written out as Mosquitto's ACL file
 * (./mosquitto-config.ts), so both brokers enforce one policy. Pure, no I/O.
 *
 * `{arm}` in a rule is the device user's own arm id; `{user}` is the user's own name (the
 * per-user control topics: a message on `arm/arm1/control/alice` can only come from alice,
 * docs/protocol.md "Control: one operator at a time"); `+` is any arm.
 */
export const ROLES = ['viewer', 'operator', 'device', 'middleware', 'admin'] as const;
export type Role = (typeof ROLES)[number];

export interface RoleRules {
  /** Topic filters the role may subscribe to (and receive messages from). */
  read: readonly string[];
  /** Topics the role may publish to (including its last will). */
  write: readonly string[];
}

const VIEWER_READ = [
  'arm/+/status',
  'arm/+/online',
  'arm/+/operator',
  'arm/+/sim/faults',
  'arm/+/profile',
  'arm/+/feedback',
  'arm/+/camera/+',
  // A camera's calibration (docs/protocol.md § Cameras): the pose and fov operators set by eye.
  'arm/+/camera/+/calibration',
  // Who holds each arm (retained) and the control events (docs/protocol.md § Control).
  'arm/+/holder',
  'arm/+/audit',
  // The thermal model's early warnings, raised by the middleware (docs/protocol.md § A thermal
  // model of each servo).
  'arm/+/alert',
  // Each arm's summary (state, health, holder, pose) at 2 Hz: what a fleet view follows
  // (docs/protocol.md § Fleets).
  'arm/+/summary',
  // A leader arm driving the arm (`armtwin gateway --leader-of`, docs/so101.md): its pose (the
  // HUD's ghost), whether it follows, and its user's enable.
  'arm/+/leader/+',
  'arm/+/leader/+/+',
] as const;

// An operator moves an arm only on its own control topic, and claims it on its own claim topic:
// the plain `arm/+/control` is not theirs (the controller could not tell who sent it).
const OPERATOR_WRITE = [
  'arm/+/control/{user}',
  'arm/+/claim/{user}',
  'arm/+/operator',
  'arm/+/request',
  'arm/+/request/{user}',
  'arm/+/sim',
  'arm/+/torque',
  'arm/+/camera/+/calibration',
  // The leader arm of this user (`armtwin gateway --leader-of ARM --user {user}`, logged in as
  // the user): its pose, its state (and last will), and its enable after a stop.
  'arm/+/leader/{user}',
  'arm/+/leader/{user}/+',
] as const;

export const ROLE_RULES: Record<Role, RoleRules> = {
  viewer: { read: VIEWER_READ, write: [] },
  operator: {
    read: VIEWER_READ,
    // `arm/+/torque`: a bus arm's torque off (`0`) and on (`1`), through its gateway.
    // `arm/+/camera/+/calibration`: a camera's pose and fov as set by eye (retained), never
    // the announcement itself, which only the camera's device may write.
    write: OPERATOR_WRITE,
  },
  // An operator that may also take an arm outright, whoever holds it.
  admin: { read: VIEWER_READ, write: [...OPERATOR_WRITE, 'arm/+/override/{user}'] },
  device: {
    read: [
      'arm/{arm}/control',
      'arm/{arm}/control/+',
      'arm/{arm}/claim/+',
      'arm/{arm}/override/+',
      'arm/{arm}/operator',
      'arm/{arm}/sim',
      'arm/{arm}/request',
      'arm/{arm}/request/+',
      'arm/{arm}/torque',
    ],
    write: [
      'arm/{arm}/status',
      'arm/{arm}/online',
      'arm/{arm}/sim/faults',
      'arm/{arm}/profile',
      'arm/{arm}/feedback',
      // The arm's cameras (PROTOCOL.md §7): the camera server logs in as the arm's device.
      'arm/{arm}/camera/+',
      'arm/{arm}/holder',
      'arm/{arm}/audit',
      'arm/{arm}/summary',
    ],
  },
  middleware: {
    read: [
      'arm/+/status',
      'arm/+/control',
      'arm/+/control/+',
      'arm/+/audit',
      'arm/+/profile',
      // The camera announcements, to record each camera (docs/cameras-recording.md); its
      // Foxglove server (FOXGLOVE_PORT, docs/foxglove.md) also shows them and watches with this
      // account who holds each arm (its users' claims), the thermal warnings and the motion
      // feedback (the plans' end poses), as a viewer.
      'arm/+/camera/+',
      'arm/+/holder',
      'arm/+/alert',
      'arm/+/feedback',
    ],
    // Its thermal watch's early warnings (docs/protocol.md § A thermal model of each servo).
    write: ['arm/+/alert'],
  },
};

/** What a connected client is. `arm` is set for (and only for) devices. */
export interface Principal {
  name: string;
  role: Role;
  arm?: string;
}

/** The rules of one principal, with `{arm}` and `{user}` filled in. */
export function rulesFor(p: Principal): RoleRules {
  const r = ROLE_RULES[p.role];
  const fill = (t: string) => t.replaceAll('{arm}', p.arm ?? '').replaceAll('{user}', p.name);
  return { read: r.read.map(fill), write: r.write.map(fill) };
}

/** MQTT topic matching: does the topic name match the filter (`+`, `#`)? */
export function topicMatches(filter: string, topic: string): boolean {
  if (topic.startsWith('$') !== filter.startsWith('$')) return false;
  const f = filter.split('/');
  const t = topic.split('/');
  for (let i = 0; i < f.length; i++) {
    if (f[i] === '#') return true;
    if (i >= t.length) return false;
    if (f[i] !== '+' && f[i] !== t[i]) return false;
  }
  return f.length === t.length;
}

/**
 * Is every topic the subscription `sub` can match also matched by the rule `rule`? So a rule
 * `arm/+/status` admits `arm/+/status` and `arm/arm1/status`, never `arm/#` or `#`.
 */
export function filterWithin(sub: string, rule: string): boolean {
  const s = sub.split('/');
  const r = rule.split('/');
  for (let i = 0; i < r.length; i++) {
    if (r[i] === '#') return true;
    if (i >= s.length) return false;
    if (s[i] === '#') return false;
    if (r[i] === '+') continue;
    if (s[i] !== r[i]) return false;
  }
  return s.length === r.length;
}

/** `$share/<group>/<filter>` → `<filter>` (the group is no one's business but the broker's). */
export function stripShare(filter: string): string {
  const m = /^\$share\/[^/+#]+\/(.+)$/.exec(filter);
  return m ? m[1]! : filter;
}

export function canPublish(p: Principal, topic: string): boolean {
  return rulesFor(p).write.some((rule) => topicMatches(rule, topic));
}

export function canSubscribe(p: Principal, filter: string): boolean {
  const f = stripShare(filter);
  return rulesFor(p).read.some((rule) => filterWithin(f, rule));
}
