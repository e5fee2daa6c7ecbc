/**
 * MQTT topics ⇄ the NATS subjects NATS's MQTT support files them under (nats-server's
 * `mqttToNATSSubjectConversion` and `natsSubjectToMQTTTopic`, server/mqtt.go): `/` separates
 * levels in MQTT and `.` in NATS, so a `.` inside a level is written `//`, and an empty level
 * (a leading, trailing or doubled `/`) is written `/.` or `./`. Wildcards: `+` ⇄ `*`, `#` ⇄ `>`.
 * Every QoS 1 message an MQTT client publishes is stored in the JetStream stream `$MQTT_msgs`
 * under `$MQTT.msgs.<subject>` before the publisher gets its PUBACK. Pure, no I/O.
 */

/** The stream NATS's MQTT keeps every QoS 1 and 2 message in. */
export const MQTT_MSGS_STREAM = '$MQTT_msgs';
/** The prefix of that stream's subjects. */
export const MQTT_MSGS_PREFIX = '$MQTT.msgs.';

/** An MQTT topic or topic filter → its NATS subject (as nats-server converts it). */
export function topicToSubject(topic: string): string {
  if (/[\s\x7f]/.test(topic))
    throw new Error(`NATS cannot carry this topic: ${JSON.stringify(topic)}`);
  let out = '';
  for (let i = 0; i < topic.length; i++) {
    const c = topic[i]!;
    if (c === '/') {
      if (i === 0 || out.endsWith('.')) out += '/.';
      else if (i === topic.length - 1 || topic[i + 1] === '/') out += './';
      else out += '.';
    } else if (c === '.') out += '//';
    else if (c === '+') out += '*';
    else if (c === '#') out += '>';
    else out += c;
  }
  return out.endsWith('.') ? `${out}/` : out;
}

/** A NATS subject (of a published message: no wildcards) → its MQTT topic. */
export function subjectToTopic(subject: string): string {
  let out = '';
  for (let i = 0; i < subject.length; i++) {
    const c = subject[i]!;
    if (c === '/' && i < subject.length - 1 && (subject[i + 1] === '.' || subject[i + 1] === '/')) {
      out += subject[i + 1] === '.' ? '/' : '.';
      i++;
    } else if (c === '/') continue;
    else out += c === '.' ? '/' : c;
  }
  return out;
}
