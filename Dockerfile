# A cluster worker (docs/batch.md#container-image): Debian 12's Python 3.11 with the
# self-contained wheel and the engines, nothing else. Build it from the project root after
# tools/build_wheel.sh, which leaves the wheel in build/dist:
#   docker build -t garment-retarget-worker .
#   docker build --build-arg EXTRAS=dask -t garment-retarget-worker .    (without Ray)
# The driver runs the same Python version (3.11) and the same wheel.
FROM debian:12-slim

RUN apt-get update \
    && apt-get install -y --no-install-recommends python3 python3-venv \
    && rm -rf /var/lib/apt/lists/*
RUN python3 -m venv /opt/garment-retarget
ENV PATH=/opt/garment-retarget/bin:$PATH

ARG EXTRAS=dask,ray
COPY build/dist/garment_retarget-*.whl /tmp/wheel/
RUN pip install --no-cache-dir --disable-pip-version-check "$(ls /tmp/wheel/garment_retarget-*.whl)[$EXTRAS]" \
    && rm -rf /tmp/wheel \
    && "$(python -c 'import garment_retarget as gr; print(gr.program_path())')" --version
