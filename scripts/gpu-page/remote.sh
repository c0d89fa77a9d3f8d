#!/bin/bash
# On the remote GPU machine (prepare.sh beside this file lays out its three folders), as root:
#   remote.sh a1            keeps the first half of the shell's package in /opt/parts
#   remote.sh a2            joins the halves and unpacks the shell into /opt/chs
#   remote.sh b COMMAND...  unpacks node, the libraries and the project into /opt, and runs COMMAND in the project
#                           with TVF_CHROMIUM, TVF_GPU_ARGS and the GPU's Vulkan driver set
#   remote.sh c COMMAND...  (prepare.sh --cores; no browser) unpacks node, tvf and its libraries, the wasm
#                           build and two meshes, and runs COMMAND in that project
# The three run on one warm machine, one right after the other: /opt is all they share.
set -euo pipefail
cd "$(dirname "$0")"; stage=$1; shift
case $stage in
  a1) mkdir -p /opt/parts && cp part /opt/parts/part1 && ls -la /opt/parts ;;
  a2)
    [ -f /opt/parts/part1 ] || { echo "remote.sh a2: no first half: run a1 first on the same warm machine"; exit 3; }
    cat /opt/parts/part1 part > /opt/parts/chs.deb && mkdir -p /opt/chs /tmp/chsx
    dpkg-deb -x /opt/parts/chs.deb /tmp/chsx && cp -r /tmp/chsx/usr/lib/chromium/* /opt/chs/
    rm -rf /tmp/chsx /opt/parts && ls /opt/chs ;;
  b)
    [ -x /opt/chs/chromium-headless-shell ] || { echo "remote.sh b: no /opt/chs: run a1 and a2 first"; exit 3; }
    xz -dc node.xz > /opt/node && chmod +x /opt/node
    mkdir -p /opt/b && xz -dc b.tar.xz | tar xf - -C /opt/b && cp -rn /opt/b/chs/* /opt/chs/
    # Without a fontconfig file the renderer aborts at the first text it lays out.
    printf '<?xml version="1.0"?><fontconfig><dir>/opt/b/fonts</dir><cachedir>/tmp/fc</cachedir></fontconfig>' \
      > /opt/b/fonts.conf
    icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
    export PATH=/opt:$PATH LD_LIBRARY_PATH=/opt/b/lib FONTCONFIG_FILE=/opt/b/fonts.conf
    export TVF_CHROMIUM=/opt/chs/chromium-headless-shell VK_ICD_FILENAMES=$icd VK_DRIVER_FILES=$icd
    export TVF_GPU_ARGS='--use-angle=vulkan --enable-features=Vulkan,VulkanFromANGLE,DefaultANGLEVulkan
      --ignore-gpu-blocklist --enable-gpu --no-sandbox --disable-dev-shm-usage'
    cd /opt/b/proj && "$@" ;;
  c)
    xz -dc node.xz > /opt/node && chmod +x /opt/node && mkdir -p /opt/c && xz -dc c.tar.xz | tar xf - -C /opt/c
    export PATH=/opt:$PATH LD_LIBRARY_PATH=/opt/c/lib
    cd /opt/c/proj && "$@" ;;
  *) echo "remote.sh: a1, a2, b or c"; exit 2 ;;
esac
