# Sourced on the lent GPU machine after tools/device-bundle.sh's folders were
# carried: installs the GL loaders, unpacks the other libraries privately.
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
mkdir -p /tmp/devlibs
for f in .devlibs/*.deb; do dpkg -x "$f" /tmp/devlibs; done
export LD_LIBRARY_PATH=/tmp/devlibs/usr/lib/x86_64-linux-gnu:/tmp/devlibs/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export PATH="$PWD/.devbin:$PATH"
