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
 * on port 44818 (cip::kMaxSessions). Class 3 (explicit) CIP connections ride on these TCP
 * connections. ODVA recommends at least 3. */
#define IPE_MAX_ENIP_SESSIONS 8

/* IPE_ENIP_TCP_CONNECTIONS: TCP connections the encapsulation server serves on 44818
 * (cip::kMaxTcpConnections): one per session plus one, so that a client beyond the session limit
 * still gets RegisterSession's status 0x0002 (and ListIdentity) instead of a reset. Only the 8
 * connections holding a session can carry CIP requests (and so large replies). */
#define IPE_ENIP_TCP_CONNECTIONS (IPE_MAX_ENIP_SESSIONS + 1)

/* IPE_MAX_CIP_CONNECTIONS: concurrent CIP connections (Class 1 implicit I/O and Class 3). Class 1
 * traffic uses a single UDP PCB on port 2222 whatever the number of connections, so this limit
 * costs lwIP no PCBs. */
#define IPE_MAX_CIP_CONNECTIONS 16

/* IPE_MAX_MODBUS_CLIENTS: concurrent Modbus TCP client connections on port 502. */
#define IPE_MAX_MODBUS_CLIENTS 8

/* IPE_MAX_HTTP_CLIENTS: concurrent HTTP connections on port 80 (web::kMaxHttpClients): a browser
 * loading the page fetches the stylesheet and the two scripts at once. */
#define IPE_MAX_HTTP_CLIENTS 3

/* IPE_PROTOCOL_TCP_CONNECTIONS: TCP connections of the card's fieldbus protocol. c500 selects ONE
 * protocol: port 502 and port 44818 are never open at the same time (switching closes the other
 * port and resets its connections), so the pools cover the larger of the two, not their sum. */
#define IPE_PROTOCOL_TCP_CONNECTIONS \
  (IPE_ENIP_TCP_CONNECTIONS > IPE_MAX_MODBUS_CLIENTS ? IPE_ENIP_TCP_CONNECTIONS : IPE_MAX_MODBUS_CLIENTS)

/* IPE_TCP_CONNECTIONS: every TCP connection the card serves at its limits at the same time. */
#define IPE_TCP_CONNECTIONS (IPE_PROTOCOL_TCP_CONNECTIONS + IPE_MAX_HTTP_CLIENTS)

/* IPE_TCP_REFUSAL_HEADROOM: PCBs beyond the limits, so that one more client than allowed (the 9th
 * Modbus client, the 10th EtherNet/IP connection, the 4th busy HTTP client) still completes its
 * handshake, reaches the accept callback and is refused cleanly (RST, or HTTP 503 then FIN) instead
 * of its SYN being dropped silently while the pool is exhausted. 3 = one per open listening port
 * (the protocol port and port 80) plus one spare. */
#define IPE_TCP_REFUSAL_HEADROOM 3

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

/* IPE_HEAP_SEGMENT_OVERHEAD: heap one queued TCP segment (or outgoing UDP datagram) costs beyond
 * its data, with TCP_OVERSIZE 0: the pbuf header (16 bytes on Cortex-M, 24 on a 64-bit host), room
 * for the Ethernet, IPv4 and TCP headers (54, aligned to 56) and the heap block header (8): 80 on the
 * card, 88 on the host. The larger is used, so the host runs with at most the card's margin. */
#define IPE_HEAP_SEGMENT_OVERHEAD 88

/* IPE_ENIP_REPLY_BYTES: the largest encapsulation reply, cip::kMaxReplyMessage (24-byte header +
 * 600 bytes of data; a static_assert in eip_service.cc keeps them equal). 624 > TCP_MSS: two
 * segments. */
#define IPE_ENIP_REPLY_BYTES 624

/* IPE_ENIP_SESSIONLESS_REPLY_BYTES: the largest reply a connection without a session can get: a
 * ListIdentity reply (about 100 bytes with a 32-character product name); RegisterSession's 0x0002
 * refusal and the error replies are 24-28 bytes. CIP requests need a session. */
#define IPE_ENIP_SESSIONLESS_REPLY_BYTES 128

/* IPE_MODBUS_ADU_BYTES: the largest Modbus TCP ADU, modbus::kMaxAduBytes (MBAP 7 + PDU 253). */
#define IPE_MODBUS_ADU_BYTES 260

/* IPE_MODBUS_UNACKED_BYTES: firmware::ModbusTcpService::kMaxUnacknowledgedBytes: what a Modbus
 * client may have unacknowledged (two largest ADUs, in at most 2 segments). */
#define IPE_MODBUS_UNACKED_BYTES (2 * IPE_MODBUS_ADU_BYTES)

/* IPE_HEAP_ENIP / IPE_HEAP_MODBUS: heap for the replies of the protocol in use. EtherNet/IP and
 * Modbus TCP are request/response: one largest reply in flight per session (in 2 segments), one
 * small one on the connection beyond the sessions; for Modbus the binding's own limit (2 answers in
 * 2 segments). A client that pipelines may have more in flight (up to TCP_SND_BUF); when the heap
 * runs out, tcp_write fails and the binding keeps the reply and writes it on the next
 * acknowledgement: nothing is lost, that client is only slowed down. */
#define IPE_HEAP_ENIP                                                                               \
  ((IPE_MAX_ENIP_SESSIONS * (IPE_ENIP_REPLY_BYTES + 2 * IPE_HEAP_SEGMENT_OVERHEAD)) +               \
   ((IPE_ENIP_TCP_CONNECTIONS - IPE_MAX_ENIP_SESSIONS) * (IPE_ENIP_SESSIONLESS_REPLY_BYTES + IPE_HEAP_SEGMENT_OVERHEAD)))
#define IPE_HEAP_MODBUS (IPE_MAX_MODBUS_CLIENTS * (IPE_MODBUS_UNACKED_BYTES + 2 * IPE_HEAP_SEGMENT_OVERHEAD))

/* IPE_HEAP_HTTP: a full send buffer per HTTP client: TCP_SND_BUF bytes of a copied JSON answer in up
 * to 4 segments (the head is copied too; asset bodies are referenced from flash and cost only their
 * segment headers), plus 256 bytes for the busy client answered 503 from flash (one header pbuf). */
#define IPE_HEAP_HTTP ((IPE_MAX_HTTP_CLIENTS * (TCP_SND_BUF + 4 * IPE_HEAP_SEGMENT_OVERHEAD)) + 256)

/* IPE_HEAP_TRANSIENT_BYTES: heap for frames that live only until the netif has copied them: a DHCP
 * message (548 bytes + headers, about 640), ACK/RST/ARP/IGMP frames (about 100 bytes each), UDP
 * replies on 44818 (ListIdentity about 100 bytes; the two delayed broadcast replies), produced Class 1
 * datagrams (under 64 bytes with the card's assemblies), and the one packet kept per unresolved ARP
 * entry. (Received frames, also an ICMP echo answered in place, are in PBUF_POOL.) */
#define IPE_HEAP_TRANSIENT_BYTES 2048

/* MEM_SIZE: size of lwIP's heap (PBUF_RAM). It holds copied TCP send data (tcp_write with
 * TCP_WRITE_FLAG_COPY) until acknowledged and outgoing UDP/ICMP/IGMP/DHCP frames until sent: the
 * replies of the protocol c500 selects (the larger share of the two), the HTTP clients' send
 * buffers and transient frames. = 6616 + 4528 + 2048 = 13192 bytes. */
#define MEM_SIZE                                                                         \
  ((IPE_HEAP_ENIP > IPE_HEAP_MODBUS ? IPE_HEAP_ENIP : IPE_HEAP_MODBUS) + IPE_HEAP_HTTP + \
   IPE_HEAP_TRANSIENT_BYTES)

/* MEMP_NUM_PBUF: PBUF_ROM/PBUF_REF headers (pbufs pointing at data not owned by lwIP, e.g.
 * tcp_write without TCP_WRITE_FLAG_COPY of constant web content). Sized so every HTTP client and the
 * busy one answered 503 can have a full send queue of such references. */
#define MEMP_NUM_PBUF ((IPE_MAX_HTTP_CLIENTS + 1) * TCP_SND_QUEUELEN)

/* MEMP_NUM_UDP_PCB: UDP PCBs: the IPE_UDP_PCBS_USED above plus 3 spare (e.g. a separate PCB for
 * multicast Class 1 production with its own TTL, a BOOTP/SNTP-style helper, a test hook). */
#define MEMP_NUM_UDP_PCB (IPE_UDP_PCBS_USED + 3)

/* MEMP_NUM_TCP_PCB: active TCP PCBs = 9 EtherNet/IP connections (or 8 Modbus clients) + 3 HTTP +
 * IPE_TCP_REFUSAL_HEADROOM (= 15). TIME_WAIT needs no slots of its own: when the pool is empty,
 * tcp_alloc() reclaims the oldest TIME_WAIT PCB (then LAST_ACK, then CLOSING) before giving up, so
 * connections closed by the card (which enter TIME_WAIT for 2*TCP_MSL) never block a new client. A
 * new connection never evicts a live one of the same or higher priority (tcp_setprio), so keep all
 * listeners at the same priority. */
#define MEMP_NUM_TCP_PCB (IPE_TCP_CONNECTIONS + IPE_TCP_REFUSAL_HEADROOM)

/* MEMP_NUM_TCP_PCB_LISTEN: listening PCBs: 502, 44818, 80, plus 1 spare. */
#define MEMP_NUM_TCP_PCB_LISTEN (IPE_TCP_LISTENERS + 1)

/* MEMP_NUM_TCP_SEG: TCP segments queued for sending or awaiting acknowledgement, all connections
 * together. Request/response connections (sessions, Modbus) have one reply outstanding, at most
 * 2 segments; an HTTP client, and the busy one, may fill its whole send queue (TCP_SND_QUEUELEN).
 * Exhausted (a pipelining client), tcp_write fails and the reply waits in the binding. */
#define MEMP_NUM_TCP_SEG \
  ((IPE_PROTOCOL_TCP_CONNECTIONS * 2) + ((IPE_MAX_HTTP_CLIENTS + 1) * TCP_SND_QUEUELEN))

/* MEMP_NUM_IGMP_GROUP: IGMP group entries: 224.0.0.1 (all-systems, always joined while
 * NETIF_FLAG_IGMP is set) plus IPE_MULTICAST_GROUPS. lwIP requires > 1. */
#define MEMP_NUM_IGMP_GROUP (1 + IPE_MULTICAST_GROUPS)

/* MEMP_NUM_SYS_TIMEOUT: simultaneously active sys_timeout() entries: lwIP's own cyclic timers
 * (LWIP_NUM_SYS_TIMEOUT_INTERNAL = TCP + ARP + 2 DHCP + IGMP = 5 with these options; it is
 * computed by opt.h from the options, so it follows them) plus IPE_APP_SYS_TIMEOUTS. */
#define MEMP_NUM_SYS_TIMEOUT (LWIP_NUM_SYS_TIMEOUT_INTERNAL + IPE_APP_SYS_TIMEOUTS)

/* PBUF_POOL_BUFSIZE: size of one receive pbuf: one full TCP segment (TCP_MSS + 40 bytes of IP/TCP
 * headers + 14 bytes Ethernet header = 590, aligned: 592), so TCP data is never a chain. Longer
 * frames (UDP datagrams up to 1514 bytes, e.g. a DHCP offer or broadcast traffic) are a chain of up
 * to 3: card_netif.cc allocates PBUF_POOL chains and every consumer copies with pbuf_copy_partial or
 * walks the chain. */
#define PBUF_POOL_BUFSIZE LWIP_MEM_ALIGN_SIZE(TCP_MSS + 40 + PBUF_LINK_ENCAPSULATION_HLEN + PBUF_LINK_HLEN)

/* PBUF_POOL_SIZE: receive pbufs. The event loop hands frames to lwIP one at a time and every service
 * copies TCP and UDP data out in its callback and frees the pbuf (no recv callback refuses data,
 * TCP_QUEUE_OOSEQ is 0, IP_REASSEMBLY is 0), so a frame is freed before the next one is read. 8 =
 * one longest frame (3 pbufs) being processed plus 5 held elsewhere: an ICMP echo or other reply
 * waiting in the ARP table for its peer's address (one per entry), a frame the netif driver has
 * queued. About 4.7 KiB. When the pool is empty a received frame is dropped and counted
 * (rx_dropped_no_pbuf); TCP retransmits it. */
#define PBUF_POOL_SIZE 8

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
 * (referenced: a heap or pool pbuf stays allocated until then) and sent when the reply arrives. Request/response protocols have one
 * packet in flight per peer, TCP retransmits anyway, and no MEMP_NUM_ARP_QUEUE pool is needed. */
#define ARP_QUEUEING 0

/* ETHARP_TRUST_IP_MAC: 0 = the ARP cache is only updated from ARP packets, not from the source
 * addresses of arbitrary IP packets (harder to poison). */
#define ETHARP_TRUST_IP_MAC 0

/* ETHARP_SUPPORT_VLAN: 1 = ethernet_input takes 802.1Q-tagged frames, as LWIP_HOOK_VLAN_CHECK
 * (lwip_hooks.h) allows: priority-tagged IPv4 only (VLAN ID 0), what a peer whose QoS object has
 * 802.1Q tagging on sends (docs/network.md "QoS (DSCP)"). Other VLANs and tagged ARP are dropped (ARP
 * must pass the ArpGuard untagged). The card's own tags are inserted by the netif, not by lwIP: without
 * LWIP_HOOK_VLAN_SET, PBUF_LINK_HLEN stays 14. */
#define ETHARP_SUPPORT_VLAN 1

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

/* TCP_MSS: 536, the IPv4 default MSS (RFC 879/1122) that every host accepts, and lwIP's own default.
 * The card's TCP traffic is small request/response messages (a Modbus ADU is at most 260 bytes, an
 * encapsulated CIP message at most 624) and a 22 KiB web page; a segment of 536 costs a receive pbuf of
 * 592 bytes instead of 1520 and keeps TCP_WND, TCP_SND_BUF and the heap small. The web page takes
 * about 45 segments instead of 16: a few milliseconds more on a LAN. */
#define TCP_MSS 536

/* TCP_WND: receive window, one TCP_MSS (536). Each binding copies received bytes into a buffer of
 * its own of at least TCP_WND bytes (static_asserts in the bindings: Modbus 536, EtherNet/IP 536,
 * HTTP a whole request) and reopens the window only by bytes it has consumed, so nothing is ever
 * refused back to lwIP and no receive pbuf stays with a connection. It must cover one largest
 * Modbus ADU twice over: lwIP reopens a window only in steps of TCP_WND / 2 (silly window
 * avoidance, tcp_update_rcv_ann_wnd), so a buffer holding a partial 260-byte ADU must still free
 * TCP_WND / 2 by answering the complete ADUs before it (536 - 259 = 277 >= 268). An EtherNet/IP
 * message longer than the window arrives in several windows (the assembler keeps it). */
#define TCP_WND TCP_MSS

/* TCP_SND_BUF: send buffer per connection, 2 * TCP_MSS (= 1072, lwIP's minimum for smooth
 * operation). The bindings feed a request/response core only while its largest answer fits (Modbus
 * also limits itself to 2 answers unacknowledged); HTTP answers are streamed from the tcp_sent
 * callback. */
#define TCP_SND_BUF (2 * TCP_MSS)

/* TCP_SND_QUEUELEN: pbufs queued for sending per connection; lwIP's formula (4 * TCP_SND_BUF /
 * TCP_MSS, rounded up) = 8, at least the 2 * TCP_SND_BUF / TCP_MSS lwIP requires. */
#define TCP_SND_QUEUELEN ((4 * (TCP_SND_BUF) + (TCP_MSS - 1)) / (TCP_MSS))

/* TCP_OVERSIZE: 0 = tcp_write allocates exactly the bytes written. lwIP's default (TCP_MSS) rounds
 * every copied write up to a whole segment so that later writes can be appended: a 12-byte Modbus
 * answer would hold 536 bytes of heap until acknowledged, and the heap shares above assume exact
 * allocation. The card's writes are whole answers, so there is little to append anyway. */
#define TCP_OVERSIZE 0

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

#if MEMP_NUM_TCP_PCB < (IPE_ENIP_TCP_CONNECTIONS + IPE_MAX_HTTP_CLIENTS + 2) || \
    MEMP_NUM_TCP_PCB < (IPE_MAX_MODBUS_CLIENTS + IPE_MAX_HTTP_CLIENTS + 2)
#error "MEMP_NUM_TCP_PCB must cover the protocol's and the HTTP clients plus one to refuse on each port"
#endif
#if IPE_ENIP_TCP_CONNECTIONS <= IPE_MAX_ENIP_SESSIONS
#error "IPE_ENIP_TCP_CONNECTIONS must exceed the sessions, or the 9th RegisterSession gets a reset, not 0x0002"
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
#if (TCP_WND - (IPE_MODBUS_ADU_BYTES - 1)) < (TCP_WND / 2)
#error "TCP_WND too small: a window holding a partial Modbus ADU could never reopen (see TCP_WND)"
#endif
#if MEM_SIZE < ((IPE_MAX_ENIP_SESSIONS * IPE_ENIP_REPLY_BYTES) + (IPE_MAX_HTTP_CLIENTS * TCP_SND_BUF))
#error "MEM_SIZE too small for one reply per session and a send buffer per HTTP client"
#endif
#if TCP_OVERSIZE != 0
#error "the heap shares assume exact allocation (TCP_OVERSIZE 0)"
#endif
#if (MEM_ALIGNMENT & (MEM_ALIGNMENT - 1)) != 0 || MEM_ALIGNMENT < 4
#error "MEM_ALIGNMENT must be a power of two, at least 4"
#endif

#endif /* IPE_LWIPOPTS_H */
