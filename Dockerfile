# AVK Station serving the simulator. The build stage runs the project's own scripts in their lean
# mode: the compile dependencies only (no test frameworks, no Chromium, no Node test tooling), the
# `avk` binary without the tests and benchmarks, and the dashboard's runtime npm package (Plotly).
# The runtime stage holds only the binary, the dashboard, the examples and runtime libraries.
#   docker build -t avk-station .
#   docker run --rm -p 8080:8080 -v avk-data:/var/lib/avk avk-station
# (README.md, "Docker": where the token is and how to open the dashboard with it.)
FROM debian:12 AS build
WORKDIR /src
COPY . .
RUN bash scripts/setup --runtime-build \
 && AVK_WEB_DEPS=runtime bash scripts/build -DAVK_BUILD_TESTS=OFF -DAVK_BUILD_BENCH=OFF

FROM debian:12-slim
# A fixed uid and gid, 999 (what `useradd --system` picked here before, so existing volumes keep
# their owner): a bind-mounted folder must be writable by it (README.md, "Docker").
RUN apt-get update \
 && apt-get install -y --no-install-recommends libsqlite3-0 libzstd1 curl \
 && rm -rf /var/lib/apt/lists/* \
 && groupadd --system --gid 999 avk \
 && useradd --system --uid 999 --gid 999 --create-home --home-dir /var/lib/avk \
      --shell /usr/sbin/nologin avk
COPY --from=build /src/build/server/avk /usr/local/bin/avk
# The dashboard's files only: not its tests or npm manifests.
COPY --from=build /src/web/index.html /src/web/favicon.svg /opt/avk/web/
COPY --from=build /src/web/css /opt/avk/web/css
COPY --from=build /src/web/js /opt/avk/web/js
COPY --from=build /src/web/node_modules/plotly.js-dist-min /opt/avk/web/node_modules/plotly.js-dist-min
COPY --from=build /src/examples /opt/avk/examples
USER avk
WORKDIR /var/lib/avk
VOLUME ["/var/lib/avk"]
EXPOSE 8080
HEALTHCHECK --interval=10s --timeout=3s --start-period=5s \
  CMD curl -fsS http://127.0.0.1:8080/api/v1/health || exit 1
# The container's port is published on purpose, so the server binds every interface; control
# endpoints still need the token printed at start (and stored in /var/lib/avk/station.db.token).
ENTRYPOINT ["avk", "serve", "--db", "/var/lib/avk/station.db", "--sim", "--bind", "0.0.0.0", "--port", "8080", "--web", "/opt/avk/web"]
