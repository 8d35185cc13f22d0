# The two entry points of README.md. Both install what the build needs (cmake for the
# vendored SUNDIALS, libclang for bindgen) when it is missing, so a fresh Debian machine
# needs nothing else.

EXAMPLE ?= fourbar
APT_PACKAGES := cmake libclang1-14 libclang-common-14-dev

.PHONY: deps example test

# Installs the system packages the build needs, only when one is missing.
deps:
	@missing=""; \
	for p in $(APT_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO=sudo; \
	  $$SUDO apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y --no-install-recommends $$missing; \
	fi

# Builds and runs the main example (writes its PNG into the current directory).
example: deps
	cargo run --release --example $(EXAMPLE)

# Runs the whole test suite (unit, integration, doc and compile-fail tests).
test: deps
	cargo test --workspace
