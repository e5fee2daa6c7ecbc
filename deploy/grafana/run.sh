#!/usr/bin/env bash
# Starts Grafana with armtwin's datasources (Flux and InfluxQL) and dashboards provisioned. The defaults live here
# (Grafana's provisioning expands $VAR but has no ${VAR:-default}); override any of them:
#
#   ARMTWIN_INFLUX_URL=http://influx:8086 deploy/grafana/run.sh
#
# Uses a local `grafana` (or `grafana-server`) binary if there is one, else Docker.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

export ARMTWIN_INFLUX_URL="${ARMTWIN_INFLUX_URL:-http://localhost:8086}"
export ARMTWIN_INFLUX_ORG="${ARMTWIN_INFLUX_ORG:-}"           # 2.x: your org; 1.8: ''
export ARMTWIN_INFLUX_BUCKET="${ARMTWIN_INFLUX_BUCKET:-armtwin/autogen}"
export ARMTWIN_INFLUX_TOKEN="${ARMTWIN_INFLUX_TOKEN:-}"       # 2.x: API token; 1.8: '' or user:password
# The InfluxQL datasource (1.8, 2.x, 3.x): the database (2.x: the bucket's name; 3.x: the
# database), and a user and password (2.x and 3.x take any user with the token as the password).
export ARMTWIN_INFLUX_DB="${ARMTWIN_INFLUX_DB:-armtwin}"
export ARMTWIN_INFLUX_USER="${ARMTWIN_INFLUX_USER:-}"
export ARMTWIN_INFLUX_PASSWORD="${ARMTWIN_INFLUX_PASSWORD:-}"
GRAFANA_PORT="${GRAFANA_PORT:-3000}"
GRAFANA_IMAGE="${GRAFANA_IMAGE:-grafana/grafana-oss:11.6.0}"

if command -v grafana >/dev/null || command -v grafana-server >/dev/null; then
  export ARMTWIN_DASHBOARDS_DIR="$HERE/dashboards"
  export GF_PATHS_PROVISIONING="$HERE/provisioning"
  export GF_PATHS_DATA="${GF_PATHS_DATA:-$HERE/.data}"
  export GF_SERVER_HTTP_PORT="$GRAFANA_PORT"
  HOMEPATH="${GRAFANA_HOME:-/usr/share/grafana}"
  if command -v grafana >/dev/null; then exec grafana server --homepath "$HOMEPATH"; fi
  exec grafana-server --homepath "$HOMEPATH"
fi

# In Docker, localhost is the container: reach an influxd on the host through host-gateway.
DOCKER_URL="${ARMTWIN_INFLUX_URL/localhost/host.docker.internal}"
DOCKER_URL="${DOCKER_URL/127.0.0.1/host.docker.internal}"
exec docker run --rm -p "$GRAFANA_PORT:3000" \
  --add-host=host.docker.internal:host-gateway \
  -e ARMTWIN_INFLUX_URL="$DOCKER_URL" \
  -e ARMTWIN_INFLUX_ORG -e ARMTWIN_INFLUX_BUCKET -e ARMTWIN_INFLUX_TOKEN \
  -e ARMTWIN_INFLUX_DB -e ARMTWIN_INFLUX_USER -e ARMTWIN_INFLUX_PASSWORD \
  -e ARMTWIN_DASHBOARDS_DIR=/var/lib/grafana/dashboards/armtwin \
  -v "$HERE/provisioning:/etc/grafana/provisioning:ro" \
  -v "$HERE/dashboards:/var/lib/grafana/dashboards/armtwin:ro" \
  "$GRAFANA_IMAGE"
