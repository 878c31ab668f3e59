# AVK Station serving the simulator. The build stages run the project's own scripts in their lean
# mode: the compile dependencies only (no test frameworks, no Chromium, no Node test tooling), the
# `avk` binary without the tests and benchmarks, and the dashboard's runtime npm package (Plotly).
# The runtime stage holds only the binary, the dashboard, the examples and runtime libraries.
#   docker build -t avk-station .
#   docker run --rm -p 8080:8080 -v avk-data:/var/lib/avk avk-station
# (README.md, "Docker": where the token is, how to open the dashboard with it, host names and
# bind mounts.)
#
# Each step copies in only what it reads, so Docker's cache keeps them apart: the dependencies
# are reinstalled only when scripts/setup changes, the npm package only when web/package*.json
# change, and the 12-minute compile only when CMakeLists.txt or a library folder changes; the
# dashboard's files and the examples go straight into the runtime stage. The npm package and the
# compile are stages of their own on top of the dependencies, so a failed `npm ci` or a new
# lockfile never redoes the compile. .dockerignore keeps everything else (docs, README, tests,
# benchmarks) out of the build context.

# The build dependencies, from the setup script alone.
FROM debian:12 AS deps
WORKDIR /src
COPY scripts/setup scripts/setup
RUN bash scripts/setup --runtime-build

# The dashboard's runtime npm package (Plotly, not the browser-test tooling), from its manifests.
FROM deps AS web
COPY scripts/web-deps scripts/web-deps
COPY web/package.json web/package-lock.json web/
RUN AVK_WEB_DEPS=runtime bash scripts/web-deps

# The `avk` binary, from the build script, CMakeLists.txt and the library folders it builds.
FROM deps AS build
COPY scripts/build scripts/build
COPY CMakeLists.txt CMakeLists.txt
COPY kinematics kinematics
COPY vehicle vehicle
COPY sim sim
COPY store store
COPY mission mission
COPY app app
COPY server server
RUN AVK_WEB_DEPS=none bash scripts/build -DAVK_BUILD_TESTS=OFF -DAVK_BUILD_BENCH=OFF

FROM debian:12-slim
# A fixed uid and gid, 999 (what `useradd --system` picked here before, so existing volumes keep
# their owner): a bind-mounted folder must be writable by it (README.md, "Docker").
# The runtime libraries avk links: SQLite, zstd (MCAP), libgps (gpsd's client, AIS traffic), libpq
# (a PostgreSQL store).
RUN apt-get update \
 && apt-get install -y --no-install-recommends libsqlite3-0 libzstd1 libgps28 libpq5 curl \
 && rm -rf /var/lib/apt/lists/* \
 && groupadd --system --gid 999 avk \
 && useradd --system --uid 999 --gid 999 --create-home --home-dir /var/lib/avk \
      --shell /usr/sbin/nologin avk
COPY --from=build /src/build/server/avk /usr/local/bin/avk
# The dashboard's files only (not its tests or npm manifests), from the context: a change to them
# rebuilds nothing before this.
COPY web/index.html web/favicon.svg /opt/avk/web/
COPY web/css /opt/avk/web/css
COPY web/js /opt/avk/web/js
COPY --from=web /src/web/node_modules/plotly.js-dist-min /opt/avk/web/node_modules/plotly.js-dist-min
COPY examples /opt/avk/examples
USER avk
WORKDIR /var/lib/avk
VOLUME ["/var/lib/avk"]
EXPOSE 8080
HEALTHCHECK --interval=10s --timeout=3s --start-period=5s \
  CMD curl -fsS http://127.0.0.1:8080/api/v1/health || exit 1
# The container's port is published on purpose, so the server binds every interface; control
# endpoints still need the token printed at start (and stored in /var/lib/avk/station.db.token).
# Host names the server answers to besides IP literals and localhost: -e AVK_ALLOW_HOSTS=a,b.
ENTRYPOINT ["avk", "serve", "--db", "/var/lib/avk/station.db", "--sim", "--bind", "0.0.0.0", "--port", "8080", "--web", "/opt/avk/web"]
