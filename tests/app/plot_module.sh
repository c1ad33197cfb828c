#!/usr/bin/env bash
# plot_module.sh MODULE TEST.py — runs the tests of the plot module (python/phasor_plot.py) with the
# Python that phasor uses (src/app/plot.h): $PHASOR_PYTHON, else python3, else /usr/bin/python3,
# the first that has matplotlib and numpy (scripts/install-deps.sh installs python3-matplotlib).
set -u
module=$1 test=$2
for py in ${PHASOR_PYTHON:-python3 /usr/bin/python3}; do
    if "$py" -c "import matplotlib, numpy" 2>/dev/null; then
        exec "$py" -B "$test" "$module"
    fi
done
echo "no Python with matplotlib and numpy found (apt-get install python3-matplotlib)"
exit 1
