#!/usr/bin/env bash
# Start / stop a throw-away ONE-NODE Slurm cluster on localhost (for tests/CI).
#
#   local_cluster.sh start STATE_DIR   start munged + slurmctld + slurmd; print
#                                      "export ..." lines (and nothing else) on stdout
#   local_cluster.sh stop  STATE_DIR   stop the daemons started for STATE_DIR (idempotent)
#   local_cluster.sh check             exit 0 if the needed binaries exist, else 77
#
# Typical use:
#   eval "$(scripts/slurm/local_cluster.sh start "$dir")"   # sets SLURM_CONF
#   sbatch --wait --wrap 'hostname'
#   scripts/slurm/local_cluster.sh stop "$dir"
#
# No systemd, no cgroups, no accounting; everything (config, munge key/socket,
# state, spool, logs, pid files) lives under STATE_DIR. A private munged with its
# own key and socket is used, so a system-wide munge (if any) is not touched.
# Debian 12 packages: slurmctld slurmd slurm-client munge.
#
# STATE_DIR must be new, empty, or a folder this script made before (it writes
# STATE_DIR/.local_cluster-state first): anything else is refused (exit 2), so a
# user's own files are never touched. Only what the script makes is removed.
set -euo pipefail

PATH="$PATH:/usr/sbin:/sbin:/usr/local/sbin"
# Do not let an outer Slurm environment leak into the daemons or our clients.
unset SLURM_CONF SLURM_JOB_ID SLURM_JOBID 2>/dev/null || true

START_TIMEOUT=${LOCAL_SLURM_START_TIMEOUT:-60}
STOP_TIMEOUT=${LOCAL_SLURM_STOP_TIMEOUT:-30}
# Seconds a finished job stays visible (squeue/scontrol; there is no accounting).
# Trade-off: `sbatch --wait` polls after 2,8,32,32.. s when MinJobAge >= 6, but
# every 2 s when MinJobAge <= 5 (then finished jobs vanish after 5..~65 s).
MIN_JOB_AGE=${LOCAL_SLURM_MIN_JOB_AGE:-300}
REQUIRED_BINS=(slurmctld slurmd sbatch squeue sinfo scontrol munged)

log() { echo "local_cluster: $*" >&2; }
die() { log "ERROR: $*"; exit 1; }
# Bad input (a folder that is not ours, a planted link): exit 2, before any side effect.
refuse() { log "ERROR: $*"; exit 2; }

usage() {
    echo "usage: $0 start STATE_DIR | stop STATE_DIR | check" >&2
    exit 2
}

cmd_check() {
    local missing=() b
    for b in "${REQUIRED_BINS[@]}"; do
        command -v "$b" >/dev/null 2>&1 || missing+=("$b")
    done
    if ((${#missing[@]})); then
        echo "local_cluster: missing: ${missing[*]}" \
             "(Debian: apt-get install slurmctld slurmd slurm-client munge)"
        exit 77
    fi
    return 0
}

# ---------------------------------------------------------------- paths ----
# The marker start writes into a state folder before anything else: a folder
# holding it (a regular file, ours, with this first line) was made by this script.
MARKER_NAME=.local_cluster-state
MARKER_TEXT="state folder of scripts/slurm/local_cluster.sh"
# What start makes in STATE (and so removes first, when re-starting there).
OWN_ENTRIES=(munge ctld spool log run slurm.conf plugstack.conf)
# Files stop removes (the daemons' pid files, the name of the short link folder).
OWN_FILES=(run/slurmd.pid run/slurmctld.pid munge/munged.pid run/shortlink)

# Sets STATE (DIR resolved: absolute, no link, no ..), CONF, LINKFILE, MARKER.
# Creates nothing: a DIR that does not exist yet resolves to the path it will have.
setup_paths() {
    local dir=$1
    [[ -n $dir ]] || refuse "STATE_DIR is empty"
    if [[ -e $dir || -L $dir ]] && [[ ! -d $dir ]]; then
        refuse "$dir: not a folder"
    fi
    STATE=$(realpath -m -- "$dir") || refuse "$dir: cannot resolve the path"
    # STATE is written unquoted into slurm.conf (where # starts a comment and blanks
    # separate keys, and Slurm expands % in file names): plain characters only.
    [[ $STATE =~ ^[A-Za-z0-9._+@~/-]+$ ]] ||
        refuse "$dir: the state folder's path ($STATE) may hold only letters, digits and . _ + @ ~ / -"
    CONF="$STATE/slurm.conf"
    LINKFILE="$STATE/run/shortlink"
    MARKER="$STATE/$MARKER_NAME"
}

# True if STATE holds the marker this script writes (see MARKER_NAME).
state_is_ours() {
    local line
    [[ -f $MARKER && ! -L $MARKER && -O $MARKER ]] && read_first line "$MARKER" &&
        [[ $line == "$MARKER_TEXT" ]]
}

state_is_empty() { [[ -d $STATE && -z $(ls -A -- "$STATE") ]]; }

# start may use STATE if it does not exist, is empty, or was made by this script.
check_claimable() {
    [[ -e $STATE ]] || return 0
    state_is_ours || state_is_empty ||
        refuse "$STATE is not empty and was not made by local_cluster.sh (no $MARKER_NAME):" \
               "refusing to use it, nothing in it was touched; give a new or empty folder"
}

# Every path the script removes in STATE must be what it made there: no link
# (it makes none in STATE), neither the path nor a folder on the way to it.
check_own_paths() {
    local rel part path parts
    for rel in "${OWN_ENTRIES[@]}" "${OWN_FILES[@]}"; do
        path=$STATE
        IFS=/ read -ra parts <<<"$rel"
        for part in "${parts[@]}"; do
            path+=/$part
            [[ ! -L $path ]] ||
                refuse "$path is a symbolic link, which local_cluster.sh never makes: refusing to touch $STATE"
        done
    done
}

# Creates STATE if needed and marks it as ours (set -C: never through a link).
claim_state() {
    mkdir -p -- "$STATE"
    state_is_ours || (set -C; echo "$MARKER_TEXT" >"$MARKER") ||
        refuse "could not write $MARKER"
}

# Removes STATE/REL (REL: one of OWN_ENTRIES or OWN_FILES) after checking, at the
# moment of removal, that it is not a link and that its folder, resolved, lies
# inside STATE. rm -r does not follow links below it; it stays on this file system.
remove_ours() {
    local rel=$1 path=$STATE/$1 parent
    [[ /$rel/ != */../* ]] || refuse "internal: '$rel' holds .."
    [[ -e $path || -L $path ]] || return 0
    [[ ! -L $path ]] || refuse "$path is a symbolic link, which local_cluster.sh never makes: not removed"
    parent=$(realpath -e -- "${path%/*}") || refuse "cannot resolve ${path%/*}"
    [[ $parent == "$STATE" || $parent == "$STATE"/* ]] ||
        refuse "$path lies outside $STATE once resolved: not removed"
    rm -rf --one-file-system -- "$path"
}

# True if folder $1 is a temp folder a short link may live in, resolved
# (TMPDIR may differ between start and stop; /tmp is always accepted).
is_temp_base() {
    [[ $1 == "$(realpath -m -- "${TMPDIR:-/tmp}")" || $1 == "$(realpath -m /tmp)" ]]
}

# The short link folder's path holds only plain characters (see setup_paths).
check_temp_base() {
    local base
    ((${#STATE} > 60)) || return 0   # no short link (choose_runroot)
    base=$(realpath -m -- "${TMPDIR:-/tmp}")
    [[ $base =~ ^[A-Za-z0-9._+@~/-]+$ ]] ||
        refuse "TMPDIR ($base) may hold only letters, digits and . _ + @ ~ / -"
}

# Sets RUNROOT, the path the daemons reach STATE by. Unix socket paths (munge
# socket and slurmstepd sockets in SlurmdSpoolDir) are limited to ~107 bytes, so
# if STATE is long we reach it through a short symlink /tmp/lslurm.XXXXXX/s -> STATE.
choose_runroot() {
    if ((${#STATE} <= 60)); then
        RUNROOT=$STATE
    else
        local tmp
        tmp=$(mktemp -d "${TMPDIR:-/tmp}/lslurm.XXXXXX")
        tmp=$(realpath -e -- "$tmp")   # recorded resolved: stop compares it as is
        chmod 700 "$tmp"
        ln -s "$STATE" "$tmp/s"
        RUNROOT="$tmp/s"
        (set -C; echo "$tmp" >"$LINKFILE")
    fi
}

# Why folder $1 is not one choose_runroot made (nothing printed if it is, or if
# it is gone). run/shortlink, which names it, can be changed by anyone who can
# write STATE, so the name is not trusted: the folder must be canonical (no link
# on the way, no ..), directly in a temp folder, named like mktemp's lslurm.XXXXXX,
# ours, and hold exactly one entry, the link s to STATE.
shortdir_problem() {
    local tmp=$1
    [[ ${tmp##*/} =~ ^lslurm\.[A-Za-z0-9]{6}$ ]] || { echo "not named lslurm.XXXXXX"; return; }
    is_temp_base "${tmp%/*}" || { echo "not directly in the temp folder"; return; }
    [[ -e $tmp || -L $tmp ]] || return 0
    [[ -d $tmp && ! -L $tmp && $(realpath -e -- "$tmp") == "$tmp" ]] ||
        { echo "not a folder (a link, or reached through one)"; return; }
    [[ -O $tmp ]] || { echo "not owned by $(id -un)"; return; }
    [[ -L $tmp/s && $(readlink -- "$tmp/s") == "$STATE" ]] || { echo "holds no link s to $STATE"; return; }
    [[ $(ls -A -- "$tmp") == s ]] || { echo "holds more than the link s"; return; }
}

# Sets SHORTDIR to the short link folder named in run/shortlink (empty if none),
# refusing (exit 2) one this script did not make.
check_shortlink() {
    local why
    SHORTDIR=
    [[ -e $LINKFILE || -L $LINKFILE ]] || return 0
    [[ -f $LINKFILE && ! -L $LINKFILE ]] || refuse "$LINKFILE: not a regular file"
    read_first SHORTDIR "$LINKFILE" || refuse "$LINKFILE: cannot read it"
    why=$(shortdir_problem "$SHORTDIR")
    [[ -z $why ]] || refuse "$LINKFILE names '$SHORTDIR', $why: not a folder local_cluster.sh" \
                            "made, nothing removed"
}

# Removes the folder check_shortlink accepted: the link s alone, then the folder
# with rmdir, which leaves it if anything else appeared in it.
remove_shortlink() {
    if [[ -n $SHORTDIR && -d $SHORTDIR ]]; then
        rm -f -- "$SHORTDIR/s"
        rmdir -- "$SHORTDIR" || log "left $SHORTDIR: it is not empty"
    fi
    remove_ours run/shortlink
}

# ---------------------------------------------------------------- stop -----
# First line of a file, using builtins only (no fork; /proc files lack a final \n).
read_first() { local -n _out=$1; _out=; { read -r _out || true; } <"$2"; } 2>/dev/null

# True if pid exists and is not a zombie (our daemons are re-parented to init,
# which may reap them late; kill -0 succeeds on zombies).
pid_alive() {
    local line rest
    [[ -n ${1:-} ]] && read_first line "/proc/$1/stat" && [[ -n $line ]] || return 1
    rest=${line##*) }
    [[ ${rest%% *} != [ZX] ]]
}

# pid from pidfile, only if that process' command line mentions $2 (guards
# against killing an unrelated process that reused the pid).
pid_from_file() {
    local pidfile=$1 marker=$2 pid
    [[ -r $pidfile ]] || return 1
    pid=$(tr -cd '0-9' <"$pidfile")
    [[ -n $pid ]] && pid_alive "$pid" || return 1
    tr '\0' ' ' <"/proc/$pid/cmdline" 2>/dev/null | grep -qF -- "$marker" || return 1
    echo "$pid"
}

# stop_daemon NAME PIDFILE MARKER; PIDFILE relative to STATE (one of OWN_FILES).
stop_daemon() {
    local name=$1 rel=$2 marker=$3 pidfile=$STATE/$2 pid i
    pid=$(pid_from_file "$pidfile" "$marker") || { remove_ours "$rel"; return 0; }
    kill -TERM "$pid" 2>/dev/null || true
    for ((i = 0; i < STOP_TIMEOUT * 10; i++)); do
        pid_alive "$pid" || break
        sleep 0.1
    done
    if pid_alive "$pid"; then
        log "$name (pid $pid) did not exit after ${STOP_TIMEOUT}s, sending SIGKILL"
        kill -KILL "$pid" 2>/dev/null || true
        for ((i = 0; i < 50; i++)); do pid_alive "$pid" || break; sleep 0.1; done
    fi
    remove_ours "$rel"
}

# slurmstepd processes of our slurmd: they keep SlurmdLogFile open.
our_stepds() {
    local d fd comm
    for d in /proc/[0-9]*; do
        read_first comm "$d/comm" || continue
        [[ $comm == slurmstepd ]] || continue
        for fd in "$d"/fd/*; do
            if [[ $(readlink "$fd" 2>/dev/null) == "$STATE/log/slurmd.log" ]]; then
                pid_alive "${d#/proc/}" && echo "${d#/proc/}"
                break
            fi
        done
    done
    return 0
}

# Print the given pids and all their descendants.
with_descendants() {
    local -A kids=()
    local d line rest ppid pid queue=("$@") out=()
    for d in /proc/[0-9]*; do
        read_first line "$d/stat" || continue
        [[ -n $line ]] || continue
        rest=${line##*) }; rest=${rest#* }; ppid=${rest%% *}
        kids[$ppid]+=" ${d#/proc/}"
    done
    while ((${#queue[@]})); do
        pid=${queue[0]}; queue=("${queue[@]:1}")
        out+=("$pid")
        # shellcheck disable=SC2206
        [[ -n ${kids[$pid]:-} ]] && queue+=(${kids[$pid]})
    done
    echo "${out[@]}"
}

# Normally slurmstepd exits right after its job; if slurmd died hard they (and
# their job processes) can linger: kill those process trees.
stop_stepds() {
    local i pids
    for ((i = 0; i < 30; i++)); do
        pids=$(our_stepds)
        [[ -z $pids ]] && return 0
        sleep 0.1
    done
    # shellcheck disable=SC2086
    pids=$(with_descendants $pids)
    log "killing leftover slurmstepd process trees: $pids"
    # shellcheck disable=SC2086
    kill -KILL $pids 2>/dev/null || true
}

# Stops what start started in DIR. Before anything: DIR must be a folder start
# made (or nothing to stop), holding no planted link or short link folder name.
cmd_stop() {
    [[ -e $1 || -L $1 ]] || return 0
    setup_paths "$1"
    if ! state_is_ours; then
        state_is_empty && return 0
        refuse "$STATE was not made by local_cluster.sh (no $MARKER_NAME): nothing stopped," \
               "nothing removed"
    fi
    check_own_paths
    check_shortlink
    # Cancel leftover jobs (needs both daemons) so no job processes outlive slurmd.
    if [[ -f $CONF ]] && pid_from_file "$STATE/run/slurmctld.pid" "$CONF" >/dev/null &&
       pid_from_file "$STATE/run/slurmd.pid" "$CONF" >/dev/null; then
        local jobs
        jobs=$(SLURM_CONF=$CONF timeout 10 squeue -h -o %A 2>/dev/null | tr '\n' ' ') || true
        if [[ -n ${jobs// /} ]]; then
            # shellcheck disable=SC2086
            SLURM_CONF=$CONF timeout 10 scancel $jobs >/dev/null 2>&1 || true
            local i
            for ((i = 0; i < 50; i++)); do
                [[ -z $(SLURM_CONF=$CONF timeout 5 squeue -h -o %A 2>/dev/null) ]] && break
                sleep 0.2
            done
        fi
    fi
    stop_daemon slurmd run/slurmd.pid "$CONF"
    stop_stepds
    stop_daemon slurmctld run/slurmctld.pid "$CONF"
    stop_daemon munged munge/munged.pid "$STATE/munge/munged.pid"
    remove_shortlink
    return 0
}

# ---------------------------------------------------------------- start ----
port_in_use() {
    local hex
    hex=$(printf ':%04X ' "$1")
    cat /proc/net/tcp /proc/net/tcp6 2>/dev/null | awk '{print $2" "}' | grep -qF -- "$hex"
}

pick_ports() {
    local base tries=0
    while ((tries++ < 200)); do
        base=$((20000 + (RANDOM % 5000) * 2))   # below the ephemeral range
        if ! port_in_use "$base" && ! port_in_use $((base + 1)); then
            CTLD_PORT=$base
            SLURMD_PORT=$((base + 1))
            return 0
        fi
    done
    die "could not find two free TCP ports"
}

show_logs() {
    local f
    for f in "$STATE/munge/munged.log" "$STATE/log/slurmctld.log" "$STATE/log/slurmd.log" \
             "$STATE/log/slurmctld.out" "$STATE/log/slurmd.out" "$STATE/log/munged.out"; do
        [[ -s $f ]] || continue
        echo "----- tail -n 30 $f -----" >&2
        tail -n 30 "$f" >&2 || true
    done
}

fail_start() {
    log "ERROR: $*"
    show_logs
    cmd_stop "$STATE" >/dev/null 2>&1 || true
    exit 1
}

write_conf() {
    local ncpu
    ncpu=$(nproc)
    cat >"$CONF" <<EOF
# Generated by local_cluster.sh -- one-node test cluster, do not edit.
ClusterName=localtest
SlurmctldHost=$NODE(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
DisableRootJobs=NO
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$RUNROOT/munge/munged.sock
StateSaveLocation=$STATE/ctld
SlurmdSpoolDir=$RUNROOT/spool
SlurmctldPidFile=$STATE/run/slurmctld.pid
SlurmdPidFile=$STATE/run/slurmd.pid
SlurmctldLogFile=$STATE/log/slurmctld.log
SlurmdLogFile=$STATE/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
PlugStackConfig=$STATE/plugstack.conf
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SlurmdParameters=config_overrides
ReturnToService=2
SchedulerParameters=batch_sched_delay=0
InactiveLimit=0
KillWait=5
MinJobAge=$MIN_JOB_AGE
NodeName=$NODE NodeHostname=$NODE NodeAddr=127.0.0.1 CPUs=$ncpu State=UNKNOWN
PartitionName=debug Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF
    : >"$STATE/plugstack.conf"
}

start_munged() {
    local m="$STATE/munge" sock="$RUNROOT/munge/munged.sock" i
    if command -v mungekey >/dev/null 2>&1; then
        mungekey --create --force --keyfile="$m/munge.key" >/dev/null 2>&1 \
            || dd if=/dev/urandom of="$m/munge.key" bs=1024 count=1 status=none
    else
        dd if=/dev/urandom of="$m/munge.key" bs=1024 count=1 status=none
    fi
    chmod 600 "$m/munge.key"
    # --force: tolerate group-writable ancestors of STATE_DIR (CI workspaces).
    setsid munged --force --socket="$sock" --key-file="$m/munge.key" \
        --pid-file="$m/munged.pid" --log-file="$m/munged.log" \
        --seed-file="$m/munged.seed" --num-threads=2 \
        </dev/null >>"$STATE/log/munged.out" 2>&1 || fail_start "munged failed to start"
    for ((i = 0; i < 100; i++)); do
        if [[ -S $sock ]] &&
           munge -n -S "$sock" 2>/dev/null | unmunge -S "$sock" >/dev/null 2>&1; then
            return 0
        fi
        sleep 0.1
    done
    fail_start "munged did not become ready (socket $sock)"
}

# Start slurmctld + slurmd; returns 2 if a port was already taken (caller retries).
start_slurm() {
    local deadline=$1 st t0=$SECONDS
    : >"$STATE/log/slurmctld.log"
    : >"$STATE/log/slurmd.log"
    setsid slurmctld -c -f "$CONF" </dev/null >>"$STATE/log/slurmctld.out" 2>&1 \
        || return 1
    for ((;;)); do
        SLURM_CONF=$CONF timeout 5 scontrol ping 2>/dev/null | grep -q 'is UP' && break
        if grep -q 'Address already in use' "$STATE/log/slurmctld.log" "$STATE/log/slurmctld.out" 2>/dev/null; then
            return 2
        fi
        if ((SECONDS - t0 > 3)) && ! pid_from_file "$STATE/run/slurmctld.pid" "$CONF" >/dev/null; then
            log "slurmctld is not running"; return 1
        fi
        ((SECONDS < deadline)) || { log "slurmctld did not answer 'scontrol ping'"; return 1; }
        sleep 0.2
    done
    t0=$SECONDS
    setsid slurmd -c -f "$CONF" -N "$NODE" </dev/null >>"$STATE/log/slurmd.out" 2>&1 \
        || return 1
    for ((;;)); do
        st=$(SLURM_CONF=$CONF timeout 5 sinfo -h -N -n "$NODE" -o '%T' 2>/dev/null | head -n1) || st=
        [[ $st == idle ]] && return 0
        if ((SECONDS - t0 > 3)) && ! pid_from_file "$STATE/run/slurmd.pid" "$CONF" >/dev/null; then
            log "slurmd is not running"; return 1
        fi
        if grep -q 'Address already in use' "$STATE/log/slurmd.log" "$STATE/log/slurmd.out" 2>/dev/null; then
            return 2
        fi
        ((SECONDS < deadline)) || { log "node '$NODE' not idle (state: '${st:-?}')"; return 1; }
        sleep 0.2
    done
}

cmd_start() {
    # Every check before any side effect: a folder that is not ours is refused (2)
    # even where Slurm is missing, and a missing Slurm (77) leaves no folder behind.
    setup_paths "$1"
    check_claimable
    check_own_paths
    check_shortlink
    check_temp_base
    cmd_check >&2   # exits 77 if binaries are missing (ctest SKIP_RETURN_CODE)
    claim_state
    SECONDS=0
    local deadline=$START_TIMEOUT attempt rc entry
    # Clean up whatever a previous run left behind (daemons and state).
    cmd_stop "$STATE" >/dev/null 2>&1 || true
    for entry in "${OWN_ENTRIES[@]}"; do remove_ours "$entry"; done
    mkdir -- "$STATE/log" "$STATE/run"
    chmod 700 "$STATE/run"
    choose_runroot
    mkdir -- "$STATE/munge" "$STATE/ctld" "$STATE/spool"
    chmod 700 "$STATE/ctld" "$STATE/spool"
    chmod 711 "$STATE/munge"   # munged: socket dir must not be group/world writable

    NODE=$(hostname -s 2>/dev/null || true)
    [[ $NODE =~ ^[A-Za-z0-9][A-Za-z0-9_-]*$ ]] || NODE=localhost

    start_munged
    for attempt in 1 2 3; do
        pick_ports
        write_conf
        rc=0
        start_slurm "$deadline" || rc=$?
        ((rc == 0)) && break
        if ((rc == 2 && attempt < 3)); then
            log "port clash on $CTLD_PORT/$SLURMD_PORT, retrying with other ports"
            stop_daemon slurmd run/slurmd.pid "$CONF"
            stop_daemon slurmctld run/slurmctld.pid "$CONF"
            continue
        fi
        fail_start "Slurm did not come up (timeout ${START_TIMEOUT}s, state dir $STATE)"
    done
    log "cluster up in ${SECONDS}s: node $NODE, $(nproc) CPUs, slurmctld port $CTLD_PORT, slurmd port $SLURMD_PORT"
    printf 'export SLURM_CONF=%q\n' "$CONF"
}

case ${1:-} in
    check) (($# == 1)) || usage; cmd_check ;;
    start) (($# == 2)) || usage; cmd_start "$2" ;;
    stop)  (($# == 2)) || usage; cmd_stop "$2" ;;
    *) usage ;;
esac
