/*
 * lwipopts.h — lwIP 2.1.3 configuration for the IPE002Z EtherNet/IP + Modbus TCP option card.
 *
 * lwIP reads this file from lwip/opt.h and takes its own default for anything not set here. Every
 * option below is documented like opt.h: NAME: what it does, and why this value. docs/lwip.md has
 * the same choices as a table.
 *
 * Shape of the port: one Ethernet netif (the card's two switch ports behind one MAC), NO_SYS=1
 * (a single event loop drives lwIP, no RTOS threads), raw/callback API only, IPv4 only, fixed
 * memory pools sized from the product limits below — no C heap anywhere in the stack.
 *
 * The same file serves the host-native Linux build and a future Cortex-M build; the only
 * difference is MEM_ALIGNMENT on 64-bit hosts (see there).
 */
#ifndef IPE_LWIPOPTS_H
#define IPE_LWIPOPTS_H

/* ================================================================================================
 * Product limits. Pool sizes below are derived from these; change a limit here, not a pool.
 * ================================================================================================
 */

/* IPE_MAX_ENIP_SESSIONS: concurrent EtherNet/IP encapsulation sessions, one TCP connection each
 * on port 44818. Class 3 (explicit) CIP connections ride on these TCP connections. */
#define IPE_MAX_ENIP_SESSIONS 8

/* IPE_MAX_CIP_CONNECTIONS: concurrent CIP connections (Class 1 implicit I/O and Class 3). Class 1
 * traffic uses a single UDP PCB on port 2222 whatever the number of connections, so this limit
 * costs lwIP no PCBs; it sizes the heap for produced (T->O) datagrams and the ARP table. */
#define IPE_MAX_CIP_CONNECTIONS 16

/* IPE_MAX_MODBUS_CLIENTS: concurrent Modbus TCP client connections on port 502. */
#define IPE_MAX_MODBUS_CLIENTS 8

/* IPE_MAX_HTTP_CLIENTS: concurrent HTTP connections on port 80 (status/configuration pages). */
#define IPE_MAX_HTTP_CLIENTS 4

/* IPE_TCP_CONNECTIONS: every TCP connection the card serves at its limits at the same time. */
#define IPE_TCP_CONNECTIONS (IPE_MAX_ENIP_SESSIONS + IPE_MAX_MODBUS_CLIENTS + IPE_MAX_HTTP_CLIENTS)

/* IPE_TCP_REFUSAL_HEADROOM: PCBs beyond the limits, so that one more client than allowed (the 9th
 * Modbus client, the 9th session, the 5th HTTP client) still completes its handshake, reaches the
 * accept callback and is refused cleanly (Modbus/ENIP/HTTP-level answer or RST) instead of its
 * SYN being dropped silently while the pool is exhausted. 4 = one per listener plus one spare, so
 * an over-limit client on every port at once is still refused cleanly. */
#define IPE_TCP_REFUSAL_HEADROOM 4

/* IPE_TCP_LISTENERS: listening PCBs: 502 (Modbus), 44818 (EtherNet/IP), 80 (HTTP). */
#define IPE_TCP_LISTENERS 3

/* IPE_UDP_PCBS_USED: UDP PCBs the firmware opens: 44818 (EtherNet/IP UDP encapsulation:
 * ListIdentity, ListServices, ...), 2222 (Class 1 I/O, all connections) and the DHCP client's
 * port 68 PCB (owned by lwIP's dhcp.c; a BOOTP client would share that role). */
#define IPE_UDP_PCBS_USED 3

/* IPE_MULTICAST_GROUPS: IPv4 multicast groups the card may join besides 224.0.0.1. Producing
 * multicast Class 1 data needs no membership; this is room for consuming multicast later. */
#define IPE_MULTICAST_GROUPS 4

/* IPE_APP_SYS_TIMEOUTS: sys_timeout() entries the firmware itself may hold at once (lwIP's own
 * cyclic timers are counted separately by LWIP_NUM_SYS_TIMEOUT_INTERNAL). */
#define IPE_APP_SYS_TIMEOUTS 4

/* ================================================================================================
 * Platform and APIs
 * ================================================================================================
 */

/* NO_SYS: 1 = no OS layer; the firmware's single event loop calls lwIP (ethernet_input,
 * sys_check_timeouts) from one context, so no threads, semaphores or mailboxes are needed. */
#define NO_SYS 1

/* SYS_LIGHTWEIGHT_PROT: 0 = no sys_arch_protect() critical sections. Nothing touches lwIP from an
 * interrupt or another thread: received frames are queued by the HAL and handed to lwIP by the
 * event loop. Turn on only if that ever changes. */
#define SYS_LIGHTWEIGHT_PROT 0

/* LWIP_TIMERS: 1 = lwIP runs its own timer list; the event loop must call sys_check_timeouts()
 * (and can use sys_timeouts_sleeptime() to know how long it may sleep). Needs sys_now(). */
#define LWIP_TIMERS 1

/* LWIP_SOCKET / LWIP_NETCONN: 0 = raw (callback) API only; both sequential APIs need NO_SYS=0. */
#define LWIP_SOCKET 0
#define LWIP_NETCONN 0

/* LWIP_RAW: 0 = no raw IP PCBs; nothing on the card speaks a protocol other than TCP/UDP/ICMP/
 * IGMP, and those are handled by lwIP itself. */
#define LWIP_RAW 0

/* LWIP_CALLBACK_API: 1 = per-PCB callbacks (tcp_recv, tcp_sent, udp_recv, ...), the raw API. */
#define LWIP_CALLBACK_API 1

/* PPP_SUPPORT / PPP_NUM_TIMEOUTS: no PPP. PPP_NUM_TIMEOUTS is part of lwIP's
 * LWIP_NUM_SYS_TIMEOUT_INTERNAL but normally defined only in netif/ppp/ppp_opts.h; defining it
 * here lets any file evaluate MEMP_NUM_SYS_TIMEOUT without including that header. */
#define PPP_SUPPORT 0
#define PPP_NUM_TIMEOUTS 0

/* LWIP_DONT_PROVIDE_BYTEORDER_FUNCTIONS: 1 = lwIP does not #define htons/htonl/ntohs/ntohl as
 * macros. Host code that also includes <arpa/inet.h> would clash with them; firmware code uses
 * lwip_htons()/lwip_htonl() explicitly, as lwIP itself does. */
#define LWIP_DONT_PROVIDE_BYTEORDER_FUNCTIONS 1

/* ================================================================================================
 * Memory: fixed pools, no C heap
 * ================================================================================================
 */

/* MEM_LIBC_MALLOC: 0 = lwIP's heap (mem_malloc, used for PBUF_RAM) is its own static array of
 * MEM_SIZE bytes, not malloc(): bounded and deterministic on the device. */
#define MEM_LIBC_MALLOC 0

/* MEMP_MEM_MALLOC: 0 = the MEMP_NUM_* pools are static arrays, not carved from the heap; running
 * out of one is visible per pool in lwip_stats.memp[] and cannot starve the others. */
#define MEMP_MEM_MALLOC 0

/* MEM_USE_POOLS: 0 = the heap is a plain first-fit heap (no custom pool list to maintain). */
#define MEM_USE_POOLS 0

/* MEM_ALIGNMENT: alignment of everything lwIP allocates. 4 on the Cortex-M target (its natural
 * word). On a 64-bit host lwIP's structures hold 8-byte pointers: with 4, a PBUF_RAM pbuf or a
 * pool element can start on a 4-byte boundary and UBSan (host-asan preset, alignment check, no
 * recovery) aborts on the misaligned pointer load, so the host uses the pointer size instead. */
#if defined(__SIZEOF_POINTER__) && (__SIZEOF_POINTER__ > 4)
#define MEM_ALIGNMENT __SIZEOF_POINTER__
#else
#define MEM_ALIGNMENT 4
#endif

/* IPE_TCP_PEER_RESPONSE_BYTES: heap held by one unacknowledged EtherNet/IP or Modbus reply,
 * rounded up: an encapsulated CIP reply (< 600 bytes) or a Modbus ADU (<= 260 bytes), plus TCP/IP/
 * Ethernet headers and the heap's own block header. These protocols are request/response, so one
 * reply per connection is outstanding at a time. */
#define IPE_TCP_PEER_RESPONSE_BYTES 1024

/* IPE_HEAP_TRANSIENT_BYTES: heap for frames that live only until the netif has copied them: a
 * produced Class 1 datagram, DHCP messages (up to 576 bytes), ARP/IGMP/ICMP replies, and the one
 * packet kept per unresolved ARP entry. */
#define IPE_HEAP_TRANSIENT_BYTES 4096

/* MEM_SIZE: size of lwIP's heap (PBUF_RAM). It holds copied TCP send data (tcp_write with
 * TCP_WRITE_FLAG_COPY) until acknowledged and outgoing UDP/ICMP/IGMP/DHCP frames until sent:
 *   one outstanding reply per EtherNet/IP session and Modbus client,
 *   a full send buffer (TCP_SND_BUF + headers) per HTTP client,
 *   and transient frames. */
#define MEM_SIZE                                                                   \
  (((IPE_MAX_ENIP_SESSIONS + IPE_MAX_MODBUS_CLIENTS) * IPE_TCP_PEER_RESPONSE_BYTES) + \
   (IPE_MAX_HTTP_CLIENTS * (TCP_SND_BUF + 512)) + IPE_HEAP_TRANSIENT_BYTES)

/* MEMP_NUM_PBUF: PBUF_ROM/PBUF_REF headers (pbufs pointing at data not owned by lwIP, e.g.
 * tcp_write without TCP_WRITE_FLAG_COPY of constant web content). Sized so every HTTP client can
 * have a full send queue of such references. */
#define MEMP_NUM_PBUF (IPE_MAX_HTTP_CLIENTS * TCP_SND_QUEUELEN)

/* MEMP_NUM_UDP_PCB: UDP PCBs: the IPE_UDP_PCBS_USED above plus 3 spare (e.g. a separate PCB for
 * multicast Class 1 production with its own TTL, a BOOTP/SNTP-style helper, a test hook). */
#define MEMP_NUM_UDP_PCB (IPE_UDP_PCBS_USED + 3)

/* MEMP_NUM_TCP_PCB: active TCP PCBs = 8 sessions + 8 Modbus + 4 HTTP + IPE_TCP_REFUSAL_HEADROOM
 * (= 24). TIME_WAIT needs no slots of its own: when the pool is empty, tcp_alloc() reclaims the
 * oldest TIME_WAIT PCB (then LAST_ACK, then CLOSING) before giving up, so connections closed by
 * the card (which enter TIME_WAIT for 2*TCP_MSL) never block a new client. A new connection never
 * evicts a live one of the same or higher priority (tcp_setprio), so keep all listeners at the
 * same priority. */
#define MEMP_NUM_TCP_PCB (IPE_TCP_CONNECTIONS + IPE_TCP_REFUSAL_HEADROOM)

/* MEMP_NUM_TCP_PCB_LISTEN: listening PCBs: 502, 44818, 80, plus 1 spare. */
#define MEMP_NUM_TCP_PCB_LISTEN (IPE_TCP_LISTENERS + 1)

/* MEMP_NUM_TCP_SEG: TCP segments queued for sending or awaiting acknowledgement, all connections
 * together. Request/response connections (sessions, Modbus) have one reply outstanding, at most
 * 2 segments; an HTTP client may fill its whole send queue (TCP_SND_QUEUELEN). */
#define MEMP_NUM_TCP_SEG \
  (((IPE_MAX_ENIP_SESSIONS + IPE_MAX_MODBUS_CLIENTS) * 2) + (IPE_MAX_HTTP_CLIENTS * TCP_SND_QUEUELEN))

/* MEMP_NUM_IGMP_GROUP: IGMP group entries: 224.0.0.1 (all-systems, always joined while
 * NETIF_FLAG_IGMP is set) plus IPE_MULTICAST_GROUPS. lwIP requires > 1. */
#define MEMP_NUM_IGMP_GROUP (1 + IPE_MULTICAST_GROUPS)

/* MEMP_NUM_SYS_TIMEOUT: simultaneously active sys_timeout() entries: lwIP's own cyclic timers
 * (LWIP_NUM_SYS_TIMEOUT_INTERNAL = TCP + ARP + 2 DHCP + IGMP = 5 with these options; it is
 * computed by opt.h from the options, so it follows them) plus IPE_APP_SYS_TIMEOUTS. */
#define MEMP_NUM_SYS_TIMEOUT (LWIP_NUM_SYS_TIMEOUT_INTERNAL + IPE_APP_SYS_TIMEOUTS)

/* PBUF_POOL_BUFSIZE: size of one receive pbuf: one full frame (TCP_MSS + 40 bytes of IP/TCP
 * headers + 14 bytes Ethernet header), so a received frame is never a chain. Aligned. */
#define PBUF_POOL_BUFSIZE LWIP_MEM_ALIGN_SIZE(TCP_MSS + 40 + PBUF_LINK_ENCAPSULATION_HLEN + PBUF_LINK_HLEN)

/* PBUF_POOL_SIZE: receive pbufs. A received frame is normally freed before the next one is read
 * (the event loop hands frames to lwIP one at a time and the firmware consumes TCP data in its
 * recv callback), so this only has to cover data a recv callback refuses (ERR_MEM, kept as
 * refused_data), a burst of frames the netif driver queues before lwIP runs, and lwIP's check
 * that TCP_WND fits in the pool. 16 frames = about 24 KiB. */
#define PBUF_POOL_SIZE 16

/* MEMP_OVERFLOW_CHECK / MEMP_SANITY_CHECK: 0 = no pool guard bytes; AddressSanitizer does not see
 * inside lwIP's static pools, set these to 1 temporarily when chasing pool corruption. */
#define MEMP_OVERFLOW_CHECK 0
#define MEMP_SANITY_CHECK 0

/* ================================================================================================
 * Link layer: Ethernet and ARP
 * ================================================================================================
 */

/* LWIP_ETHERNET / LWIP_ARP: 1 = Ethernet framing (ethernet_input/ethernet_output) and ARP. */
#define LWIP_ETHERNET 1
#define LWIP_ARP 1

/* ETH_PAD_SIZE: 0 = the Ethernet header starts at payload offset 0; the netif copies whole
 * frames, so there is no DMA alignment trick to play (lwIP's packed headers cope with the
 * resulting 2-byte offset of the IP header). */
#define ETH_PAD_SIZE 0

/* ARP_TABLE_SIZE: ARP cache entries: every TCP peer at the limits may be a different host
 * (Class 1 originators are the same scanners that hold the sessions), plus the gateway, the
 * DHCP server and spares. Only hosts the card talks to get an entry: firmware::ArpGuard keeps
 * other senders out (lwIP would recycle the oldest entry for each of them). */
#define ARP_TABLE_SIZE (IPE_TCP_CONNECTIONS + 4)

/* ARP_QUEUEING: 0 = while a peer's MAC is unresolved only its most recent outgoing packet is kept
 * (copied to the heap) and sent when the reply arrives. Request/response protocols have one
 * packet in flight per peer, TCP retransmits anyway, and no MEMP_NUM_ARP_QUEUE pool is needed. */
#define ARP_QUEUEING 0

/* ETHARP_TRUST_IP_MAC: 0 = the ARP cache is only updated from ARP packets, not from the source
 * addresses of arbitrary IP packets (harder to poison). */
#define ETHARP_TRUST_IP_MAC 0

/* ================================================================================================
 * IPv4, ICMP, IGMP, DHCP
 * ================================================================================================
 */

/* LWIP_IPV4 / LWIP_IPV6: IPv4 only; EtherNet/IP and Modbus TCP on the card are IPv4 protocols. */
#define LWIP_IPV4 1
#define LWIP_IPV6 0

/* IP_FORWARD: 0 = the card is a host, not a router. */
#define IP_FORWARD 0

/* IP_REASSEMBLY / IP_FRAG: 0 = no fragment reassembly and no fragmentation. No protocol on the
 * card needs a datagram larger than one frame (TCP segments by MSS; EtherNet/IP UDP and Class 1
 * payloads and DHCP fit in 1500 bytes), and refusing fragments removes a way to tie up receive
 * pbufs from the network. Fragments received are dropped and counted in ip stats. */
#define IP_REASSEMBLY 0
#define IP_FRAG 0

/* IP_DEFAULT_TTL: 64, the usual host default (the TCP/IP object's multicast TTL is set per PCB). */
#define IP_DEFAULT_TTL 64

/* LWIP_ICMP: 1 = answer pings (commissioning and diagnostics expect it). */
#define LWIP_ICMP 1

/* LWIP_IGMP: 1 = IGMPv2 membership reports for joined groups; EtherNet/IP networks rely on IGMP
 * snooping for multicast I/O. The netif must set NETIF_FLAG_IGMP. A real MAC also needs
 * netif->igmp_mac_filter (or all-multicast reception) to receive joined groups. */
#define LWIP_IGMP 1

/* LWIP_MULTICAST_TX_OPTIONS: 1 = per-PCB multicast TTL and interface (udp_set_multicast_ttl);
 * the TCP/IP object's "TTL Value" attribute sets the TTL of produced multicast Class 1 data.
 * lwIP requires it with LWIP_IGMP. */
#define LWIP_MULTICAST_TX_OPTIONS 1

/* LWIP_DHCP: 1 = DHCP client (the TCP/IP object's "configuration method: DHCP"). */
#define LWIP_DHCP 1

/* DHCP_DOES_ARP_CHECK: 1 = probe an offered address with ARP before using it and decline it if
 * another host answers. lwIP 2.1 has no full RFC 5227 ACD: the firmware's ACD (net/acd.h) claims
 * the bound address and defends it (docs/network.md "Addressing"). */
#define DHCP_DOES_ARP_CHECK 1

/* LWIP_HOOK_FILENAME: lwip_hooks.h adds the DHCP client identifier (option 61) and, in DISCOVER,
 * the host name (option 12) from the device name c081-c096 (LWIP_HOOK_DHCP_APPEND_OPTIONS). */
#define LWIP_HOOK_FILENAME "lwip_hooks.h"

/* LWIP_DHCP_GET_NTP_SRV: 0 = do not request NTP servers (no SNTP client on the card). */
#define LWIP_DHCP_GET_NTP_SRV 0

/* LWIP_DHCP_BOOTP_FILE: 0 = ignore the BOOTP file/sname fields. */
#define LWIP_DHCP_BOOTP_FILE 0

/* LWIP_AUTOIP: 0 = no 169.254/16 link-local fallback; EtherNet/IP devices keep their stored or
 * default address instead. */
#define LWIP_AUTOIP 0

/* LWIP_DNS: 0 = no resolver; the card never looks names up. (Consequence: lwIP does not keep the
 * DNS servers a DHCP server offers.) */
#define LWIP_DNS 0

/* LWIP_BROADCAST_PING / LWIP_MULTICAST_PING: 0 = do not answer pings to broadcast or multicast
 * addresses (smurf-style amplification). */
#define LWIP_BROADCAST_PING 0
#define LWIP_MULTICAST_PING 0

/* ================================================================================================
 * UDP and TCP
 * ================================================================================================
 */

/* LWIP_UDP: 1 = UDP (EtherNet/IP UDP encapsulation on 44818, Class 1 I/O on 2222, DHCP). */
#define LWIP_UDP 1

/* LWIP_UDPLITE: 0 = not used. */
#define LWIP_UDPLITE 0

/* LWIP_TCP: 1 = TCP (EtherNet/IP sessions, Modbus TCP, HTTP). */
#define LWIP_TCP 1

/* TCP_MSS: 1460 = 1500-byte Ethernet MTU minus 40 bytes of IPv4 and TCP headers. */
#define TCP_MSS 1460

/* TCP_WND: receive window, 2 * TCP_MSS. Requests to the card are small (Modbus ADU <= 260 bytes,
 * encapsulated CIP requests < 600 bytes, HTTP requests of a few hundred bytes) and are consumed
 * in the recv callback, so a larger window would only let a peer tie up more receive pbufs. */
#define TCP_WND (2 * TCP_MSS)

/* TCP_SND_BUF: send buffer per connection, 2 * TCP_MSS (lwIP's minimum for smooth operation).
 * Replies fit in one segment; HTTP pages are streamed from the tcp_sent callback. */
#define TCP_SND_BUF (2 * TCP_MSS)

/* TCP_SND_QUEUELEN: pbufs queued for sending per connection; lwIP's formula (4 * TCP_SND_BUF /
 * TCP_MSS, rounded up) = 8, at least the 2 * TCP_SND_BUF / TCP_MSS lwIP requires. */
#define TCP_SND_QUEUELEN ((4 * (TCP_SND_BUF) + (TCP_MSS - 1)) / (TCP_MSS))

/* TCP_QUEUE_OOSEQ: 0 = out-of-order segments are dropped instead of queued; the peer retransmits.
 * On a switched LAN reordering is rare, and queued segments would hold receive pbufs. */
#define TCP_QUEUE_OOSEQ 0

/* TCP_LISTEN_BACKLOG / TCP_DEFAULT_LISTEN_BACKLOG: 1 = limit, per listener, the connections in
 * the handshake (SYN received, not yet accepted). With the raw API the accept callback runs as
 * soon as the handshake completes, so this bounds half-open PCBs: a SYN flood on one port holds
 * at most this many (they time out after TCP_SYN_RCVD_TIMEOUT, 20 s), and SYNs beyond it are
 * dropped (the peer retransmits, Linux after 1 s). Default = the largest per-port limit (8), so
 * a scanner or test that opens all its allowed connections at once, with every SYN arriving
 * before the first handshake completes, is not delayed. A listener may choose its own with
 * tcp_listen_with_backlog(). */
#define TCP_LISTEN_BACKLOG 1
#define TCP_DEFAULT_LISTEN_BACKLOG \
  (IPE_MAX_ENIP_SESSIONS > IPE_MAX_MODBUS_CLIENTS ? IPE_MAX_ENIP_SESSIONS : IPE_MAX_MODBUS_CLIENTS)

/* LWIP_TCP_KEEPALIVE: 1 = keepalive timing can be set per PCB (pcb->keep_idle/keep_intvl/
 * keep_cnt). Keepalive runs only on PCBs where the firmware sets SOF_KEEPALIVE
 * (ip_set_option(pcb, SOF_KEEPALIVE)). */
#define LWIP_TCP_KEEPALIVE 1

/* SO_REUSE: 1 = SOF_REUSEADDR exists. The firmware sets it on its listeners (firmware/tcp_pcb_util.cc):
 * a port closed by the configuration (c500, c554) and opened again after a communication reset must
 * not be refused with ERR_USE for 2*TCP_MSL because connections the card closed are in TIME_WAIT on it
 * (seen with port 80: c554 = 0, f899, c554 = 1, f899). */
#define SO_REUSE 1

/* TCP_KEEPIDLE_DEFAULT / TCP_KEEPINTVL_DEFAULT / TCP_KEEPCNT_DEFAULT: defaults for PCBs with
 * SOF_KEEPALIVE: first probe after 60 s idle, then every 10 s, give up after 6 unanswered (a dead
 * peer is found in about 2 minutes instead of lwIP's 2 hours + 11 minutes). A PLC that was
 * power-cycled without closing its connection otherwise holds one of the 8 Modbus/session slots
 * for hours. */
#define TCP_KEEPIDLE_DEFAULT 60000UL
#define TCP_KEEPINTVL_DEFAULT 10000UL
#define TCP_KEEPCNT_DEFAULT 6U

/* ================================================================================================
 * Netif
 * ================================================================================================
 */

/* LWIP_NETIF_HOSTNAME: 1 = netif->hostname is sent as DHCP option 12 (the TCP/IP object's
 * "Host Name" attribute). netif_set_hostname() stores the pointer: the string must outlive the
 * netif. */
#define LWIP_NETIF_HOSTNAME 1

/* LWIP_NETIF_STATUS_CALLBACK: 1 = callback when the netif goes up/down or its address changes
 * (DHCP lease obtained), to update the TCP/IP object and the network status LED. */
#define LWIP_NETIF_STATUS_CALLBACK 1

/* LWIP_NETIF_LINK_CALLBACK: 1 = callback on netif_set_link_up/down (cable plugged/unplugged);
 * lwIP also restarts DHCP and sends gratuitous ARP/IGMP reports on link up. */
#define LWIP_NETIF_LINK_CALLBACK 1

/* LWIP_SINGLE_NETIF: 0 = keep the general netif list (tests may add a second netif). */
#define LWIP_SINGLE_NETIF 0

/* LWIP_NETIF_LOOPBACK / LWIP_HAVE_LOOPIF: 0 = no loopback interface; the card never talks to
 * itself. */
#define LWIP_NETIF_LOOPBACK 0
#define LWIP_HAVE_LOOPIF 0

/* LWIP_CHECKSUM_CTRL_PER_NETIF: 0 = checksum handling is global (below), not per netif. */
#define LWIP_CHECKSUM_CTRL_PER_NETIF 0

/* CHECKSUM_GEN_* / CHECKSUM_CHECK_*: 1 = every checksum is generated and verified in software;
 * neither the host TAP/slirp path nor the target MAC offloads checksums. */
#define CHECKSUM_GEN_IP 1
#define CHECKSUM_GEN_UDP 1
#define CHECKSUM_GEN_TCP 1
#define CHECKSUM_GEN_ICMP 1
#define CHECKSUM_CHECK_IP 1
#define CHECKSUM_CHECK_UDP 1
#define CHECKSUM_CHECK_TCP 1
#define CHECKSUM_CHECK_ICMP 1

/* ================================================================================================
 * Statistics and debugging
 * ================================================================================================
 */

/* LWIP_STATS: 1 = lwip_stats counters, read by the diagnostics (Ethernet Link object counters,
 * web status page, tests that check pools did not run dry). Receive-pbuf pool usage is
 * lwip_stats.memp[MEMP_PBUF_POOL] (part of MEMP_STATS); the heap is lwip_stats.mem. */
#define LWIP_STATS 1
#define LWIP_STATS_DISPLAY 0
#define LINK_STATS 1
#define ETHARP_STATS 1
#define IP_STATS 1
#define ICMP_STATS 1
#define IGMP_STATS 1
#define UDP_STATS 1
#define TCP_STATS 1
#define MEM_STATS 1
#define MEMP_STATS 1
#define SYS_STATS 0
#define MIB2_STATS 0

/* LWIP_DEBUG: deliberately not defined (lwIP tests it with #ifdef). Defining it, plus the
 * *_DEBUG switches of interest set to LWIP_DBG_ON, routes lwIP's debug output through
 * LWIP_PLATFORM_DIAG (ipe_lwip_diag). LWIP_ASSERT stays active either way (LWIP_NOASSERT is not
 * defined): a failed assertion calls ipe_lwip_assert(). */

/* ================================================================================================
 * Consistency checks linking the knobs above to the product limits. Only macros defined in this
 * file may appear in these #if lines: lwIP's own (LWIP_MEM_ALIGN_SIZE, PBUF_LINK_HLEN, ...) are
 * defined after this file is read. lwIP's core/init.c adds its own sanity checks on top (TCP
 * queue/segment/window relations, IGMP and timeout pool sizes), which fail the build of lwIP.
 * ================================================================================================
 */

#if MEMP_NUM_TCP_PCB < (IPE_MAX_ENIP_SESSIONS + IPE_MAX_MODBUS_CLIENTS + IPE_MAX_HTTP_CLIENTS + 1)
#error "MEMP_NUM_TCP_PCB must cover every session, Modbus and HTTP client plus one to refuse"
#endif
#if IPE_TCP_REFUSAL_HEADROOM < 1
#error "IPE_TCP_REFUSAL_HEADROOM must be >= 1 or an over-limit client cannot be refused cleanly"
#endif
#if TCP_DEFAULT_LISTEN_BACKLOG < 1 || TCP_DEFAULT_LISTEN_BACKLOG > MEMP_NUM_TCP_PCB
#error "TCP_DEFAULT_LISTEN_BACKLOG must be in 1..MEMP_NUM_TCP_PCB"
#endif
#if MEMP_NUM_TCP_PCB_LISTEN < IPE_TCP_LISTENERS
#error "MEMP_NUM_TCP_PCB_LISTEN must cover the listeners on 502, 44818 and 80"
#endif
#if MEMP_NUM_UDP_PCB < IPE_UDP_PCBS_USED
#error "MEMP_NUM_UDP_PCB must cover 44818, 2222 and the DHCP client"
#endif
#if MEMP_NUM_IGMP_GROUP < 2
#error "MEMP_NUM_IGMP_GROUP must exceed 1: 224.0.0.1 always takes one entry"
#endif
#if ARP_TABLE_SIZE < (IPE_TCP_CONNECTIONS + 1) || ARP_TABLE_SIZE > 127
#error "ARP_TABLE_SIZE must cover every TCP peer plus the gateway (and stay below 128)"
#endif
#if MEMP_NUM_TCP_SEG < TCP_SND_QUEUELEN
#error "MEMP_NUM_TCP_SEG must be at least TCP_SND_QUEUELEN"
#endif
#if TCP_WND > (PBUF_POOL_SIZE * TCP_MSS)
#error "PBUF_POOL_SIZE too small to hold a full TCP_WND of received data"
#endif
#if MEM_SIZE < ((IPE_MAX_ENIP_SESSIONS + IPE_MAX_MODBUS_CLIENTS + IPE_MAX_HTTP_CLIENTS) * 600)
#error "MEM_SIZE too small for one reply per TCP connection"
#endif
#if (MEM_ALIGNMENT & (MEM_ALIGNMENT - 1)) != 0 || MEM_ALIGNMENT < 4
#error "MEM_ALIGNMENT must be a power of two, at least 4"
#endif

#endif /* IPE_LWIPOPTS_H */
