"""The worst-case stack of the card image, from GCC's own figures (tools/bench/footprint uses it).

Inputs: every `.ci` file of the cross build (-fcallgraph-info=su: each function's frame, "N bytes
(static)", and its calls) and the image's disassembly for what was built without them (newlib, libgcc,
libstdc++: the frame from the prologue, the calls from `bl`/`b.w` to symbols).

Indirect calls are where a call graph is usually wrong. Each one GCC reports ("__indirect_call", with the
source location of the call) is resolved here:
  - a C++ virtual call: the name before "(" at the call's location; its targets are every virtual
    function of that name (an over-approximation: any override may be the one called);
  - lwIP's callbacks (TCP_EVENT_*, netif->output, timeouts, ...): LWIP_CALLBACKS below, the functions
    our code and lwIP register in those slots (docs/board.md "Stack").
A call that neither resolves is listed as unresolved, and the result is then a lower bound, said so.
Recursion (a cycle in the graph) is reported the same way: its depth cannot be bounded from the graph.
"""
import collections
import glob
import os
import re
import subprocess

# lwIP's function-pointer slots and who fills them on this card. Keys: the macro or member named at the
# call's source location; values: the unqualified names of the functions that may be called there (our
# TCP services register the OnRecv/OnSent/OnError/OnPoll of firmware/tcp_pcb_util.h and their OnAccept;
# the UDP users their OnUdp/BootpReceived; lwIP its own). Every name must match a function of the
# image: footprint fails when one does not, so the table cannot silently go stale.
LWIP_CALLBACKS = {
    "TCP_EVENT_ACCEPT": ["OnAccept", "tcp_accept_null"],
    "TCP_EVENT_RECV": ["OnRecv", "tcp_recv_null"],
    "TCP_EVENT_CLOSED": ["OnRecv", "tcp_recv_null"],
    "TCP_EVENT_SENT": ["OnSent"],
    "TCP_EVENT_ERR": ["OnError"],
    "TCP_EVENT_POLL": ["OnPoll"],
    "TCP_EVENT_CONNECTED": [],  # the card opens no TCP connection (no tcp_connect)
    "recv": ["OnUdp", "BootpReceived", "dhcp_recv"],  # udp.c: pcb->recv
    "input": ["ethernet_input"],  # firmware/card_netif.cc: netif->input, set by netif_add
    "NETIF_STATUS_CALLBACK": ["StatusCallback"],
    "NETIF_LINK_CALLBACK": [],
    "output": ["etharp_output"],
    "linkoutput": ["LinkOutputCallback"],
    "init": ["InitCallback"],
    "igmp_mac_filter": ["MacFilterCallback"],
    # timeouts.c: sys_check_timeouts runs lwip_cyclic_timer, which runs lwIP's cyclic timers
    "handler": ["tcp_tmr", "etharp_tmr", "dhcp_coarse_tmr", "dhcp_fine_tmr", "igmp_tmr",
                "lwip_cyclic_timer"],
    # std::all_of over a function pointer (web/http_request.cc)
    "_M_pred": ["IsTokenChar", "IsTargetChar"],
}
# Recursion the code bounds itself: the function, and the header and constant that bound how many times
# it may be on the stack at once (read from the source, so the figure follows the code).
BOUNDED_RECURSION = {
    # Unconnected_Send and Multiple Service Packet nest requests, at most kMaxNesting levels deep.
    "cip::MessageRouter::Handle": ("cip/include/cip/message_router.h", "kMaxNesting", 1),
}
HEAP = ("malloc", "_malloc_r", "calloc", "_calloc_r", "realloc", "_realloc_r", "free", "_free_r", "_sbrk",
        "_sbrk_r", "_Znwj", "_Znaj", "_ZdlPv", "_ZdaPv", "_ZdlPvj", "_ZdaPvj")


class Graph:
    def __init__(self):
        self.frame = {}      # title -> bytes
        self.label = {}      # title -> demangled name
        self.calls = collections.defaultdict(set)   # title -> titles
        self.indirect = collections.defaultdict(list)  # title -> [(path, line, column)]

    def name(self, title):
        return self.label.get(title, title)


def parse_call_graphs(build_dir, graph):
    node = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"')
    edge = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"(?: label: "([^"]+)")?')
    for path in glob.glob(os.path.join(build_dir, "**", "*.ci"), recursive=True):
        with open(path) as f:
            for line in f:
                m = node.match(line)
                if m:
                    title, label = m.group(1), m.group(2).split("\\n")
                    size = re.match(r"(\d+) bytes", label[-1])
                    if size:
                        graph.frame[title] = int(size.group(1))
                        graph.label[title] = label[0]
                    elif title not in graph.label:
                        graph.label[title] = label[0]
                    continue
                m = edge.match(line)
                if m:
                    source, target, where = m.groups()
                    if target == "__indirect_call":
                        file, row, column = where.rsplit(":", 2)
                        graph.indirect[source].append((file, int(row), int(column)))
                    else:
                        graph.calls[source].add(target)


def keep_linked(graph, nm, image):
    """Forget what the linker left out (gc-sections, objects of other targets in the build tree): a
    function counts only when the image has its symbol."""
    linked = set()
    for line in subprocess.run([nm, image], capture_output=True, text=True, check=True).stdout.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[1] in "tTwW":
            linked.add(parts[2])
    for title in list(graph.frame):
        if title.split(":")[-1] not in linked:
            del graph.frame[title]
    for title in list(graph.calls):
        if title not in graph.frame:
            del graph.calls[title]
    for title in list(graph.indirect):
        if title not in graph.frame:
            del graph.indirect[title]


def parse_disassembly(objdump, image, graph):
    """Frames and direct calls of the functions compiled without -fcallgraph-info (the libraries)."""
    text = subprocess.run([objdump, "-d", "--no-show-raw-insn", image], capture_output=True, text=True,
                          check=True).stdout
    current = None
    for line in text.splitlines():
        m = re.match(r"^[0-9a-f]+ <([^>]+)>:$", line)
        if m:
            current = m.group(1)
            known = current in graph.frame
            if not known:
                graph.frame[current] = 0
            graph.__dict__.setdefault("from_disassembly", set())
            if not known:
                graph.from_disassembly.add(current)
            continue
        if current is None or current not in getattr(graph, "from_disassembly", ()):
            continue
        m = re.search(r"\t(push|stmdb\s+sp!|vpush)(?:\.w)?\s+\{([^}]*)\}", line)
        if m:
            registers = [r for r in m.group(2).split(",") if r.strip()]
            count = 0
            for r in registers:
                span = re.match(r"\s*[rsd](\d+)-[rsd](\d+)", r)
                count += (int(span.group(2)) - int(span.group(1)) + 1) if span else 1
            width = 8 if "d" in m.group(2) else 4
            graph.frame[current] += count * width
            continue
        m = re.search(r"\tsub(?:\.w)?\s+sp, sp, #(\d+)|\tsub(?:\.w)?\s+sp, #(\d+)", line)
        if m:
            graph.frame[current] += int(m.group(1) or m.group(2))
            continue
        m = re.search(r"\t(?:bl|blx|b\.w|b)\s+[0-9a-f]+ <([^>+]+)>", line)
        if m and m.group(1) != current:
            graph.calls[current].add(m.group(1))


class TypeIndex:
    """Enough of the project's C++ to narrow a virtual call: which class derives from which, and the
    declared type of a member or variable by its name (the receiver of a call)."""

    SOURCE_DIRS = ("firmware", "hal", "cip", "modbus", "web", "net", "drive_link")

    def __init__(self, root):
        self.bases = collections.defaultdict(set)
        self.declared = collections.defaultdict(set)  # name -> type names
        self.declared_in = collections.defaultdict(lambda: collections.defaultdict(set))  # name -> file -> types
        declaration = re.compile(r"(?:const\s+)?((?:\w+::)*\w+)(?:<[^;(){}]*>)?\s*(?:const\s*)?[&*]+\s*"
                                 r"(?:const\s+)?(\w+)\s*[;=,){]")
        heading = re.compile(r"\b(?:class|struct)\s+(\w+)\s*(?:final\s*)?:\s*([^{;]+)\{")
        for directory in self.SOURCE_DIRS:
            for path in glob.glob(os.path.join(root, directory, "**", "*.[hc]*"), recursive=True):
                with open(path, errors="replace") as f:
                    text = f.read()
                for m in heading.finditer(text):
                    for base in m.group(2).split(","):
                        words = re.sub(r"<.*", "", base).split()
                        if words:
                            self.bases[m.group(1)].add(words[-1].split("::")[-1])
                for m in declaration.finditer(text):
                    self.declared[m.group(2)].add(m.group(1).split("::")[-1])
                    self.declared_in[m.group(2)][path].add(m.group(1).split("::")[-1])

    def receiver_type(self, receiver, path):
        """The declared type of `receiver`: as the caller's own files declare it (its .cc, its header),
        else as the whole tree does when every declaration agrees."""
        stem = re.sub(r"\.(cc|h)$", "", os.path.basename(path))
        local = set()
        for file, types in self.declared_in.get(receiver, {}).items():
            if re.sub(r"\.(cc|h)$", "", os.path.basename(file)) == stem:
                local |= types
        types = local or self.declared.get(receiver, set())
        return next(iter(types)) if len(types) == 1 else None

    def derived(self, base):
        """`base` and every class deriving from it, directly or not."""
        family, grew = {base}, True
        while grew:
            grew = False
            for cls, bases in self.bases.items():
                if cls not in family and bases & family:
                    family.add(cls)
                    grew = True
        return family


def class_of(label, name):
    """'virtual bool hal::FlashNvStore::Read(...)' and 'Read' -> 'FlashNvStore'."""
    head = label.split("(")[0]
    parts = re.split(r"::", head.split()[-1])
    return parts[-2] if len(parts) >= 2 else None


def unqualified(label):
    """'virtual void firmware::X::Poll(hal::Micros)' -> 'Poll'."""
    head = label.split("(")[0]
    return re.split(r"[:\s]", head)[-1]


class Analysis:
    def __init__(self, graph, source_root):
        self.graph = graph
        self.types = TypeIndex(source_root)
        self.sources = {}
        self.unresolved = collections.Counter()
        self.virtual_by_name = collections.defaultdict(set)
        self.by_unqualified = collections.defaultdict(set)
        for title, label in graph.label.items():
            if title in graph.frame:
                self.by_unqualified[unqualified(label)].add(title)
                if label.startswith("virtual "):
                    self.virtual_by_name[unqualified(label)].add(title)
        for title in graph.frame:
            self.by_unqualified.setdefault(title, set()).add(title)
        self.callbacks = {}
        self.stale_callbacks = []
        for slot, names in LWIP_CALLBACKS.items():
            targets = set()
            for name in names:
                found = self.by_unqualified.get(name, set())
                if not found:
                    self.stale_callbacks.append("%s: %s" % (slot, name))
                targets |= found
            self.callbacks[slot] = targets
        self.memo = {}
        self.cycles = []
        self.bounded = {}
        for title in graph.frame:
            bound = self.recursion_bound(title, source_root)
            if bound is not None:
                self.bounded[title] = bound

    def source_line(self, path, row):
        if path not in self.sources:
            try:
                with open(path, errors="replace") as f:
                    self.sources[path] = f.read().split("\n")
            except OSError:
                self.sources[path] = []
        lines = self.sources[path]
        return lines[row - 1] if 0 < row <= len(lines) else ""

    def indirect_targets(self, path, row, column, caller):
        line = self.source_line(path, row)
        if column - 1 < len(line) and line[column - 1] == "(":
            # C++: the location is the call's "(": the method's name and its receiver are before it.
            call = re.search(r"(?:([A-Za-z_]\w*)\s*(?:\.|->)\s*)?([A-Za-z_]\w*)\s*$", line[:column - 1])
        else:
            # C (lwIP): the location is the start of the callee expression ("netif->output", a macro).
            call = re.match(r"(?:[A-Za-z_]\w*\s*(?:\.|->)\s*)*?(?:([A-Za-z_]\w*)\s*(?:\.|->)\s*)?"
                            r"([A-Za-z_]\w*)", line[column - 1:])
        receiver, name = (call.group(1), call.group(2)) if call else (None, None)
        if name in self.callbacks:
            return self.callbacks[name] - {caller}
        targets = set()
        if name in self.virtual_by_name:
            targets = self.overrides(name, receiver, path)
        if not targets:
            # The call GCC points at may sit inside another's arguments, which may go on over the next
            # lines: every virtual called there.
            statement = " ".join(self.source_line(path, r) for r in range(row, row + 3)).split(";")[0]
            for other_receiver, other in re.findall(r"(?:([A-Za-z_]\w*)\s*(?:\.|->)\s*)?([A-Za-z_]\w*)\s*\(",
                                                    statement):
                if other in self.virtual_by_name:
                    targets |= self.overrides(other, other_receiver or None, path)
        targets.discard(caller)  # a decorator forwarding to the object it wraps, not to itself
        if not targets:
            self.unresolved["%s:%d %s" % (os.path.relpath(path), row, line.strip()[:60])] += 1
        return targets

    def overrides(self, name, receiver, path):
        """The virtuals called `name` in the classes the receiver's declared type may be, else all."""
        every = self.virtual_by_name[name]
        base = self.types.receiver_type(receiver, path) if receiver else None
        if base is None:
            return set(every)
        family = self.types.derived(base)
        narrowed = {t for t in every if class_of(self.graph.label[t], name) in family}
        return narrowed or set(every)

    def resolve(self, title):
        """A called title to the defined function: local copies are named 'file:mangled'."""
        if title in self.graph.frame:
            return title
        short = title.split(":")[-1]
        return short if short in self.graph.frame else title

    def callees(self, title):
        result = {self.resolve(t) for t in self.graph.calls.get(title, ())}
        for where in self.graph.indirect.get(title, ()):
            result |= self.indirect_targets(*where, title)
        return result

    def recursion_bound(self, title, root):
        label = self.graph.name(title)
        for function, (header, constant, offset) in BOUNDED_RECURSION.items():
            if "%s(" % function in label:
                with open(os.path.join(root, header)) as f:
                    text = f.read()
                value = re.search(r"\b%s\s*=\s*(\d+)" % constant, text)
                if value:
                    return int(value.group(1)) + offset
        return None

    def worst(self, title, path=()):
        """(bytes, [titles]) of the deepest call chain from `title`."""
        key = (title, tuple(sorted(t for t in path if t in self.bounded)))
        if key in self.memo:
            return self.memo[key]
        if title in path:
            # A cycle through a function whose nesting the code bounds is followed that many times.
            segment = path[path.index(title):]
            bounded = [t for t in set(segment) if t in self.bounded]
            if not bounded:
                self.cycles.append(segment + (title,))
                return 0, [title]
            if any(path.count(t) >= self.bounded[t] for t in bounded):
                return 0, []  # the code refuses to nest deeper
        frame = self.graph.frame.get(title, 0)
        best, best_chain = 0, []
        for callee in self.callees(title):
            depth, chain = self.worst(callee, path + (title,))
            if depth > best:
                best, best_chain = depth, chain
        result = (frame + best, [title] + best_chain)
        self.memo[key] = result
        return result


def heap_calls(graph):
    """Call sites of the heap (malloc, free, new, delete, sbrk) in the image's call graph, and apart from
    them the deleting destructors' calls of operator delete: a class with a virtual destructor gets one
    (its vtable names it), but nothing on the card is allocated, so none is ever called (and the board's
    operator delete traps: hal/mps2_an386/runtime.cc)."""
    calls, deleting = [], []
    for caller, callees in graph.calls.items():
        for callee in callees:
            if callee.split(":")[-1] in HEAP and caller in graph.frame:
                is_deleting_destructor = re.search(r"D0Ev$", caller) and callee.startswith("_ZdlPv")
                (deleting if is_deleting_destructor else calls).append((caller, callee))
    return sorted(calls), sorted(deleting)
